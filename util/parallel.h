#pragma once
// A minimal fork-join loop over [0, n) in contiguous chunks; the callers' work items (rows,
// bands, keys) are coarse, so no work stealing is needed. Items of very uneven cost (the bands of
// the kinetic grid: the events gather where the geometry moves) are handed out one at a time.
// The chunks run on the shared ThreadPool (no thread is started per call, which matters for the
// per-frame loops); a nested or concurrent call, which the pool does not take, starts threads.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "util/fork_gate.h"
#include "util/thread_pool.h"

namespace kinray {

/// Number of worker threads for a request: 0 means all cores.
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : int(n);
}

/// Calls f(begin, end) once on each of min(threads, n) contiguous chunks of [0, n), in parallel
/// (the chunks may share threads: a worker that is slow to start leaves its chunk to the others).
/// An exception thrown by f is rethrown here once every chunk has returned.
template <class F>
void parallel_chunks(size_t n, int threads, F&& f) {
  const size_t workers = std::min<size_t>(size_t(resolve_threads(threads)), std::max<size_t>(n, 1));
  if (workers <= 1) {
    f(size_t(0), n);
    return;
  }
  struct Context {
    F& f;
    size_t n, workers;
  } context{f, n, workers};
  const ThreadPool::Task chunk = [](void* c, size_t w) {
    const Context& run = *static_cast<Context*>(c);
    run.f(run.n * w / run.workers, run.n * (w + 1) / run.workers);
  };
  if (ThreadPool::shared().try_run(workers, workers - 1, chunk, &context)) return;
  std::mutex error_mutex;
  std::exception_ptr error;
  const auto guarded = [&](size_t w) {
    const ThreadBusy busy;
    try {
      f(n * w / workers, n * (w + 1) / workers);
    } catch (...) {
      std::lock_guard lock(error_mutex);
      if (!error) error = std::current_exception();
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (size_t w = 1; w < workers; ++w) pool.push_back(start_thread([&guarded, w] { guarded(w); }));
  guarded(0);
  for (auto& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

/// Calls f(i) for every i in [0, n), in parallel chunks.
template <class F>
void parallel_for(size_t n, int threads, F&& f) {
  parallel_chunks(n, threads, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) f(i);
  });
}

/// Calls f(i) for every i in [0, n) on `threads` workers, each taking the next unclaimed i: for
/// items whose costs are unknown and uneven.
template <class F>
void parallel_for_dynamic(size_t n, int threads, F&& f) {
  std::atomic<size_t> next{0};
  parallel_chunks(size_t(resolve_threads(threads)), threads, [&](size_t, size_t) {
    for (size_t i = next.fetch_add(1, std::memory_order_relaxed); i < n;
         i = next.fetch_add(1, std::memory_order_relaxed))
      f(i);
  });
}

}  // namespace kinray
