#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "util/fork_gate.h"
#include "util/parallel.h"

namespace kinray {
namespace {

// The gate's count once oneTBB's workers have left kinray's arenas (they linger briefly).
int threads_at_work_once_idle() {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (threads_at_work() != 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return threads_at_work();
}

// Uneven items handed out one at a time: each index is visited exactly once, whatever the
// number of workers (more, fewer or as many as items).
TEST(Parallel, DynamicForVisitsEveryIndexOnce) {
  for (const int threads : {1, 2, 3, 8}) {
    for (const size_t n : {size_t(0), size_t(1), size_t(5), size_t(97)}) {
      std::vector<std::atomic<int>> visits(n);
      parallel_for_dynamic(n, threads, [&](size_t i) {
        volatile double sink = 0;
        for (size_t k = 0; k < (i % 7) * 1000; ++k) sink = sink + double(k);  // uneven costs
        visits[i].fetch_add(1);
      });
      for (size_t i = 0; i < n; ++i) EXPECT_EQ(visits[i].load(), 1) << "n " << n << " i " << i;
    }
  }
}

// Exactly min(threads, n) chunks, each [n*w/W, n*(w+1)/W) once (callers keep per-chunk state),
// for chunk counts below, at and above n; n = 0 is one empty chunk.
TEST(Parallel, ChunksAreExactAndCoverTheRangeOnce) {
  for (const int threads : {1, 2, 3, 8}) {
    for (const size_t n : {size_t(0), size_t(1), size_t(2), size_t(7), size_t(1000)}) {
      const size_t chunks = std::min<size_t>(size_t(threads), std::max<size_t>(n, 1));
      std::vector<std::atomic<int>> visits(n);
      std::mutex mutex;
      std::set<std::pair<size_t, size_t>> seen;
      parallel_chunks(n, threads, [&](size_t begin, size_t end) {
        {
          const std::lock_guard lock(mutex);
          EXPECT_TRUE(seen.emplace(begin, end).second)
              << "chunk [" << begin << ", " << end << ") twice";
        }
        for (size_t i = begin; i < end; ++i) visits[i].fetch_add(1);
      });
      std::set<std::pair<size_t, size_t>> expected;
      for (size_t w = 0; w < chunks; ++w) expected.emplace(n * w / chunks, n * (w + 1) / chunks);
      EXPECT_EQ(seen, expected) << "threads " << threads << " n " << n;
      for (size_t i = 0; i < n; ++i) EXPECT_EQ(visits[i].load(), 1) << "n " << n << " i " << i;
    }
  }
}

// parallel_for visits every index once, for ranges below, at and above the grain.
TEST(Parallel, ForVisitsEveryIndexOnce) {
  for (const int threads : {0, 1, 2, 5}) {
    for (const size_t n : {size_t(0), size_t(1), size_t(3), size_t(100), size_t(100000)}) {
      std::vector<std::atomic<int>> visits(n);
      parallel_for(n, threads, [&](size_t i) { visits[i].fetch_add(1); });
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(visits[i].load(), 1) << "n " << n << " i " << i;
    }
  }
}

// With one thread every loop runs on the caller (no arena, no worker).
TEST(Parallel, OneThreadRunsOnTheCaller) {
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<int> elsewhere{0};
  const auto check = [&] {
    if (std::this_thread::get_id() != caller) ++elsewhere;
  };
  parallel_for(1000, 1, [&](size_t) { check(); });
  parallel_for_dynamic(50, 1, [&](size_t) { check(); });
  parallel_chunks(1000, 1, [&](size_t, size_t) { check(); });
  parallel_chunks(1, 4, [&](size_t, size_t) { check(); });  // one item: one chunk
  EXPECT_EQ(elsewhere.load(), 0);
}

// A throwing body reaches the caller with its own type, from every kind of loop and from a
// nested loop (in the same arena and in another one), and the loops still work afterwards.
TEST(Parallel, ExceptionsReachTheCaller) {
  EXPECT_THROW(parallel_for(100, 3,
                            [](size_t i) {
                              if (i == 57) throw std::runtime_error("body");
                            }),
               std::runtime_error);
  EXPECT_THROW(parallel_for_dynamic(100, 2,
                                    [](size_t i) {
                                      if (i == 3) throw std::out_of_range("item");
                                    }),
               std::out_of_range);
  EXPECT_THROW(parallel_chunks(10, 2,
                               [](size_t begin, size_t) {
                                 if (begin != 0) throw std::length_error("chunk");
                               }),
               std::length_error);
  for (const int inner_threads : {2, 3})
    EXPECT_THROW(parallel_for(4, 2,
                              [&](size_t) {
                                parallel_for(10, inner_threads, [](size_t k) {
                                  if (k == 9) throw std::invalid_argument("nested");
                                });
                              }),
                 std::invalid_argument);
  std::atomic<size_t> sum{0};
  parallel_for(100, 3, [&](size_t i) { sum += i; });
  EXPECT_EQ(sum.load(), 4950u);
  // Nothing is left busy after the throws (a fork would wait for it for ever).
  EXPECT_EQ(threads_at_work_once_idle(), 0);
}

// Loops nested inside a body (same thread count, and others: they run in the outer loop's
// arena; A -> B -> A would deadlock oneTBB otherwise), and loops from several threads at once,
// all complete with every item visited once.
TEST(Parallel, NestedAndConcurrentRuns) {
  for (const int inner_threads : {1, 2, 3}) {
    std::atomic<int> inner{0};
    parallel_for(6, 2, [&](size_t) { parallel_for(50, inner_threads, [&](size_t) { ++inner; }); });
    EXPECT_EQ(inner.load(), 300) << inner_threads;
  }
  std::atomic<int> deep{0};
  parallel_for_dynamic(4, 2, [&](size_t) {
    parallel_chunks(3, 3, [&](size_t, size_t) { parallel_for(5, 2, [&](size_t) { ++deep; }); });
  });
  EXPECT_EQ(deep.load(), 4 * 3 * 5);

  std::vector<std::thread> callers;
  std::vector<std::atomic<int>> totals(4);
  for (size_t c = 0; c < totals.size(); ++c)
    callers.emplace_back([&, c] {
      for (int repeat = 0; repeat < 50; ++repeat)
        parallel_for_dynamic(40, 3, [&](size_t) { ++totals[c]; });
    });
  for (auto& caller : callers) caller.join();
  for (const auto& total : totals) EXPECT_EQ(total.load(), 50 * 40);
}

// A fork waits for the loops: NoThreadBusy is taken only when no body runs and no thread is
// inside kinray's arenas, and a body started meanwhile waits until it is let go.
TEST(Parallel, NoThreadBusyWaitsForTheLoops) {
  std::atomic<bool> stop{false};
  std::atomic<int> in_body{0}, bodies{0};
  std::thread looper([&] {
    while (!stop.load())
      parallel_for_dynamic(8, 2, [&](size_t) {
        ++in_body;
        ++bodies;
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        --in_body;
      });
  });
  while (bodies.load() < 20) std::this_thread::yield();
  for (int round = 0; round < 20; ++round) {
    const NoThreadBusy quiet;
    EXPECT_EQ(in_body.load(), 0);
    const int before = bodies.load();
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
    EXPECT_EQ(bodies.load(), before) << "a body started while the gate was held";
  }
  stop = true;
  looper.join();
  // Taken inside a body, it holds nothing (the other threads may wait for this one).
  parallel_for(2, 2, [&](size_t) { const NoThreadBusy inside; });
}

}  // namespace
}  // namespace kinray
