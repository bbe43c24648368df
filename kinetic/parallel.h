#pragma once
// A minimal fork-join loop over [0, n) in contiguous chunks; the callers' work items (rows,
// bands, keys) are coarse, so no work stealing is needed. Items of very uneven cost (the bands of
// the kinetic grid: the events gather where the geometry moves) are handed out one at a time.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <thread>
#include <vector>

namespace kinray {

/// Number of worker threads for a request: 0 means all cores.
inline int resolve_threads(int requested) {
  if (requested > 0) return requested;
  const unsigned n = std::thread::hardware_concurrency();
  return n == 0 ? 1 : int(n);
}

/// Calls f(begin, end) on `threads` contiguous chunks of [0, n) in parallel.
template <class F>
void parallel_chunks(size_t n, int threads, F&& f) {
  const size_t workers = std::min<size_t>(size_t(resolve_threads(threads)), std::max<size_t>(n, 1));
  if (workers <= 1) {
    f(size_t(0), n);
    return;
  }
  std::vector<std::thread> pool;
  pool.reserve(workers - 1);
  for (size_t w = 1; w < workers; ++w)
    pool.emplace_back([&, w] { f(n * w / workers, n * (w + 1) / workers); });
  f(size_t(0), n / workers);
  for (auto& thread : pool) thread.join();
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
