// The antialiasing benchmark's events per keyframe interval: the intervals a frame range spans,
// partial ones by the fraction covered (exact answers on a hand-made key grid).
#include <gtest/gtest.h>

#include "verification/antialiasing_bench.h"

namespace kinray {
namespace {

TEST(AntialiasingBench, KeyframeIntervalsCountPartialIntervalsByTheirFraction) {
  const std::vector<double> keys = {0, 1, 2, 4};
  EXPECT_DOUBLE_EQ(keyframe_intervals(keys, 0, 4), 3);
  EXPECT_DOUBLE_EQ(keyframe_intervals(keys, 0.5, 1.5), 1);     // half of two intervals
  EXPECT_DOUBLE_EQ(keyframe_intervals(keys, 1.5, 3), 1);       // half of [1, 2], half of [2, 4]
  EXPECT_DOUBLE_EQ(keyframe_intervals(keys, 2, 2), 0);         // one frame spans nothing
  EXPECT_DOUBLE_EQ(keyframe_intervals({0.0}, 0, 1), 0);        // a static scene has one key
  EXPECT_DOUBLE_EQ(keyframe_intervals(keys, -1, 0.25), 0.25);  // outside the keys counts nothing
}

}  // namespace
}  // namespace kinray
