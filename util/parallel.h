#pragma once
// Parallel loops over [0, n) on oneTBB, the scheduler Embree runs on too: a thin wrapper over
// blocked_range with a grain size (STYLE.md). `threads` (0: all cores) picks a task_arena of
// that concurrency (at most what oneTBB runs at once: the cores), created once per distinct count
// and kept, so the per-frame loops create none. Every body runs under ThreadBusy, and the arenas'
// threads are counted, for the fork of model_guard.h (util/fork_gate.h). A loop nested in a body
// runs in the arena of the loop around it, whatever its `threads` (its chunks stay as many as
// asked): a thread waiting in arena A for a loop in arena B that needs A again would deadlock
// oneTBB (A's slots are all held by threads waiting in B). And it waits in isolation: while its
// caller waits, it runs only the nested loop's work, never another item of the loop around it (a
// body's state, say a thread's reader, is not re-entered). oneTBB hands an exception thrown by a
// body to the caller, after the bodies that had started have returned; the items not yet started
// are skipped. The bodies run in the default floating-point environment, whatever the caller's.
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/partitioner.h>
#include <oneapi/tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

#include "util/fork_gate.h"

namespace kinray {

/// Number of worker threads for a request: 0 means all cores.
int resolve_threads(int requested);

namespace parallel_detail {

/// The arena of `threads` threads (at most what oneTBB runs at once), created (and warmed up: its
/// workers have started) on first use and kept for the process's life.
tbb::task_arena& arena(int threads);

/// Ranges a parallel_for's items are cut into at most, per thread: enough for a thread that
/// starts late (the machine is shared) or items of uneven cost, few enough that a range's
/// overhead (a task) is small against its work.
inline constexpr size_t kRangesPerThread = 8;

/// The arena whose body this thread runs, if any.
inline thread_local tbb::task_arena* t_arena = nullptr;

/// Held around every body run in an arena: the thread is busy (util/fork_gate.h) and in `arena`.
class Body {
 public:
  explicit Body(tbb::task_arena& arena) : m_outer(t_arena) { t_arena = &arena; }
  ~Body() { t_arena = m_outer; }
  Body(const Body&) = delete;
  Body& operator=(const Body&) = delete;

 private:
  const ThreadBusy m_busy;
  tbb::task_arena* const m_outer;
};

/// Runs loop(arena) in the arena of `threads` threads, or, nested in a body, in that body's
/// arena; isolated (see above).
template <class Loop>
void run_in_arena(int threads, const Loop& loop) {
  tbb::task_arena& in = t_arena != nullptr ? *t_arena : arena(threads);
  in.execute([&] { tbb::this_task_arena::isolate([&] { loop(in); }); });
}

}  // namespace parallel_detail

/// Calls f(begin, end) once on each of min(threads, n) contiguous chunks [n*w/W, n*(w+1)/W) of
/// [0, n), in parallel (the chunks may share threads: one that no worker takes is run by
/// another). With one chunk, f runs on the caller.
template <class F>
void parallel_chunks(size_t n, int threads, F&& f) {
  const int resolved = resolve_threads(threads);
  const size_t chunks = std::min<size_t>(size_t(resolved), std::max<size_t>(n, 1));
  if (chunks <= 1) {
    const ThreadBusy busy;
    f(size_t(0), n);
    return;
  }
  parallel_detail::run_in_arena(resolved, [&](tbb::task_arena& arena) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, chunks, 1),
        [&](const tbb::blocked_range<size_t>& range) {
          const parallel_detail::Body body(arena);
          for (size_t w = range.begin(); w < range.end(); ++w)
            f(n * w / chunks, n * (w + 1) / chunks);
        },
        tbb::simple_partitioner());
  });
}

/// Calls f(i) for every i in [0, n), in parallel ranges of at least n / (kRangesPerThread *
/// threads) items. With one thread (or item), f runs on the caller.
template <class F>
void parallel_for(size_t n, int threads, F&& f) {
  const int resolved = resolve_threads(threads);
  if (resolved <= 1 || n <= 1) {
    const ThreadBusy busy;
    for (size_t i = 0; i < n; ++i) f(i);
    return;
  }
  const size_t grain =
      std::max<size_t>(1, n / (parallel_detail::kRangesPerThread * size_t(resolved)));
  parallel_detail::run_in_arena(resolved, [&](tbb::task_arena& arena) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, grain),
                      [&](const tbb::blocked_range<size_t>& range) {
                        const parallel_detail::Body body(arena);
                        for (size_t i = range.begin(); i < range.end(); ++i) f(i);
                      });
  });
}

/// Calls f(i) for every i in [0, n) on `threads` threads, the items handed out one at a time
/// (grain 1): for items whose costs are unknown and uneven.
template <class F>
void parallel_for_dynamic(size_t n, int threads, F&& f) {
  const int resolved = resolve_threads(threads);
  if (resolved <= 1 || n <= 1) {
    const ThreadBusy busy;
    for (size_t i = 0; i < n; ++i) f(i);
    return;
  }
  parallel_detail::run_in_arena(resolved, [&](tbb::task_arena& arena) {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, n, 1),
        [&](const tbb::blocked_range<size_t>& range) {
          const parallel_detail::Body body(arena);
          for (size_t i = range.begin(); i < range.end(); ++i) f(i);
        },
        tbb::simple_partitioner());
  });
}

}  // namespace kinray
