// The check of auto's choice of the grid (auto_backend.h, step 4): a keyframe interval hands the
// shot back to Embree only when the grid was clearly slower than Embree's measured frame.
#include <gtest/gtest.h>

#include "renderer/backends/auto_backend.h"

namespace kinray {
namespace {

TEST(AutoBackend, TheGridLosesTheShotOnlyWhenClearlySlower) {
  const double embree_frame = 0.010;  // 10 ms a frame, 16 frames an interval: 0.16 s with Embree
  EXPECT_FALSE(grid_lost_interval(0.05, 16, embree_frame));  // the grid 3x faster
  EXPECT_FALSE(
      grid_lost_interval(0.20, 16, embree_frame));  // 1.25x slower: a shared machine's noise
  EXPECT_TRUE(grid_lost_interval(0.48, 16, embree_frame));  // 3x slower: flythrough's case
  EXPECT_FALSE(grid_lost_interval(1.0, 0, embree_frame));   // no frame in the interval
  // The margin itself: just below and just above it.
  EXPECT_FALSE(grid_lost_interval(0.99 * kGridCheckMargin * 0.16, 16, embree_frame));
  EXPECT_TRUE(grid_lost_interval(1.01 * kGridCheckMargin * 0.16, 16, embree_frame));
}

}  // namespace
}  // namespace kinray
