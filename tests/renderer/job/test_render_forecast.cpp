// The kinetic-versus-Embree forecast of `kinray render`: its projections on given timings, worked
// out by hand, and when it warns.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "renderer/job/render_forecast.h"

namespace kinray {
namespace {

/// 100 frames, 10 done: the kinetic grid took 4 s to build with the first frame, the 9 later
/// frames 0.5 s each; Embree built in 0.2 s and rendered its first frame in 0.05 s.
ForecastInputs low_frame_rate() {
  return ForecastInputs{.frames_total = 100,
                        .frames_done = 10,
                        .load_s = 1,
                        .kinetic_first_s = 4,
                        .kinetic_later_s = 9 * 0.5,
                        .other_per_frame_s = 0.01,
                        .embree_setup_s = 0.2,
                        .embree_frame_s = 0.05};
}

TEST(RenderForecast, ProjectsKineticFromItsFirstFrameAndTheMeanOfItsLaterOnes) {
  // load 1 + first 4 + 99 later frames at 0.5 + 100 frames shaded at 0.01.
  EXPECT_NEAR(project_kinetic(low_frame_rate()), 1 + 4 + 99 * 0.5 + 100 * 0.01, 1e-9);
}

TEST(RenderForecast, ProjectsEmbreeFromItsSetupAndFirstFrame) {
  // load 1 + setup 0.2 + 100 frames at 0.05 rendering and 0.01 shading.
  EXPECT_NEAR(project_embree(low_frame_rate()), 1 + 0.2 + 100 * (0.05 + 0.01), 1e-9);
}

TEST(RenderForecast, WarnsOnlyWhenKineticIsLongAndManyTimesSlower) {
  const ForecastInputs in = low_frame_rate();
  EXPECT_TRUE(embree_much_faster({project_kinetic(in), project_embree(in)}));  // 55.5 s vs 7.2 s
  // Shading that dominates both (0.1 s a frame) leaves kinetic under 5x Embree: 64.5 s vs 16.2 s.
  ForecastInputs shaded = in;
  shaded.other_per_frame_s = 0.1;
  EXPECT_FALSE(embree_much_faster({project_kinetic(shaded), project_embree(shaded)}));
  // A short render is not worth a warning, however large the ratio.
  EXPECT_FALSE(embree_much_faster({.kinetic_s = 9.5, .embree_s = 0.01}));
  EXPECT_TRUE(embree_much_faster({.kinetic_s = 10.5, .embree_s = 2}));
  EXPECT_FALSE(embree_much_faster({.kinetic_s = 10.5, .embree_s = 2.2}));
}

TEST(RenderForecast, MoreFramesPerKeyIntervalFavourKinetic) {
  // The same scene at 10x the frame rate: the grid's build is shared by ten times the frames and
  // each later frame has a tenth of the events (0.05 s), while Embree pays each frame in full.
  ForecastInputs dense = low_frame_rate();
  dense.frames_total = 1000;
  dense.frames_done = 91;
  dense.kinetic_later_s = 90 * 0.05;
  const RenderForecast low{project_kinetic(low_frame_rate()), project_embree(low_frame_rate())};
  const RenderForecast high{project_kinetic(dense), project_embree(dense)};
  EXPECT_LT(high.kinetic_s / high.embree_s, low.kinetic_s / low.embree_s);
}

TEST(RenderForecast, WarningIsOneLineNamingBothTimesAndTheFlags) {
  const std::string line = forecast_warning({.kinetic_s = 36.7, .embree_s = 0.2});
  // A line for warn(), which adds the "kinray: warning: " prefix and the newline itself.
  EXPECT_EQ(line.find("kinray:"), std::string::npos) << line;
  EXPECT_EQ(std::count(line.begin(), line.end(), '\n'), 0) << line;
  EXPECT_EQ(line.rfind("the kinetic backend will take", 0), 0u) << line;
  EXPECT_NE(line.find("about 37 s"), std::string::npos) << line;
  EXPECT_NE(line.find("Embree about 0.2 s"), std::string::npos) << line;
  EXPECT_NE(line.find("--backend embree"), std::string::npos) << line;
  EXPECT_NE(line.find("--inbetweens"), std::string::npos) << line;
}

}  // namespace
}  // namespace kinray
