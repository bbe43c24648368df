// The motion blur benchmark's verdict: the targets of the blur without lights (10x Embree at 64
// samples) and with them (5x), and error at or below Embree's at 256 samples.
#include <gtest/gtest.h>

#include "verification/motion_blur_bench.h"

namespace kinray {
namespace {

MotionBlurResult result(double kinetic_ms, double kinetic_rmse, size_t lights) {
  MotionBlurResult r;
  r.lights = lights;
  r.kinetic.ms_per_frame = kinetic_ms;
  r.kinetic.rmse = kinetic_rmse;
  r.embree = {{64, 60.0, 4e-4, 0}, {256, 240.0, 1e-4, 0}};
  return r;
}

TEST(MotionBlurBench, TheTimeTargetIsTenTimesEmbree64AndFiveTimesWithLights) {
  EXPECT_TRUE(result(6, 5e-5, 0).meets_targets());    // 10x
  EXPECT_FALSE(result(10, 5e-5, 0).meets_targets());  // 6x without lights
  EXPECT_TRUE(result(10, 5e-5, 2).meets_targets());   // 6x with lights
  EXPECT_FALSE(result(15, 5e-5, 2).meets_targets());  // 4x
  EXPECT_FALSE(result(6, 2e-4, 0).meets_targets());   // error above Embree-256's
  EXPECT_EQ(result(10, 5e-5, 2).to_json()["lights"], 2);
}

}  // namespace
}  // namespace kinray
