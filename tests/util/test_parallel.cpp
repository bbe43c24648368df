#include "util/parallel.h"

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "util/thread_pool.h"

#include <gtest/gtest.h>

namespace kinray {
namespace {

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

// Every chunk once, contiguous and covering [0, n), for chunk counts below, at and above n.
TEST(Parallel, ChunksCoverTheRangeOnce) {
  for (const int threads : {2, 3, 8}) {
    for (const size_t n : {size_t(1), size_t(2), size_t(7), size_t(1000)}) {
      std::vector<std::atomic<int>> visits(n);
      std::atomic<int> chunks{0};
      parallel_chunks(n, threads, [&](size_t begin, size_t end) {
        EXPECT_LE(begin, end);
        ++chunks;
        for (size_t i = begin; i < end; ++i) visits[i].fetch_add(1);
      });
      EXPECT_EQ(chunks.load(), int(std::min<size_t>(size_t(threads), n))) << "n " << n;
      for (size_t i = 0; i < n; ++i) EXPECT_EQ(visits[i].load(), 1) << "n " << n << " i " << i;
    }
  }
}

// A throwing chunk reaches the caller (pool runs, and the nested runs that start their own
// threads), and the pool still works afterwards.
TEST(Parallel, ExceptionsReachTheCaller) {
  EXPECT_THROW(parallel_for(100, 3, [](size_t i) {
                 if (i == 57) throw std::runtime_error("chunk");
               }),
               std::runtime_error);
  EXPECT_THROW(parallel_for(4, 2, [](size_t) {
                 parallel_for(10, 2, [](size_t k) {
                   if (k == 9) throw std::invalid_argument("nested");
                 });
               }),
               std::invalid_argument);
  std::atomic<size_t> sum{0};
  parallel_for(100, 3, [&](size_t i) { sum += i; });
  EXPECT_EQ(sum.load(), 4950u);
}

// Runs nested inside a chunk, and runs from several threads at once (the pool takes one, the
// others start their own threads), all complete with every item visited once.
TEST(Parallel, NestedAndConcurrentRuns) {
  std::atomic<int> inner{0};
  parallel_for(6, 2, [&](size_t) { parallel_for(50, 2, [&](size_t) { ++inner; }); });
  EXPECT_EQ(inner.load(), 300);

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

// The workers are kept between runs: many small runs start no further threads.
TEST(Parallel, PoolKeepsItsWorkers) {
  ThreadPool pool;
  std::atomic<int> done{0};
  const ThreadPool::Task task = [](void* counter, size_t) { ++*static_cast<std::atomic<int>*>(counter); };
  ASSERT_TRUE(pool.try_run(8, 2, task, &done));
  EXPECT_EQ(pool.worker_count(), 2u);
  for (int repeat = 0; repeat < 200; ++repeat) ASSERT_TRUE(pool.try_run(8, 2, task, &done));
  EXPECT_EQ(pool.worker_count(), 2u);
  EXPECT_EQ(done.load(), 201 * 8);
  ASSERT_TRUE(pool.try_run(3, 1, task, &done));  // fewer helpers than workers
  EXPECT_EQ(done.load(), 201 * 8 + 3);
}

}  // namespace
}  // namespace kinray
