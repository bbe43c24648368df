#include "kinetic/parallel.h"

#include <atomic>
#include <vector>

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

}  // namespace
}  // namespace kinray
