// The benchmark suite as a library: which scenes it names, which keyframe intervals it measures,
// and BART's measure (the whole animation, kinetic and the best Embree mode) on a built-in scene.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "renderer/backends/embree_backend.h"
#include "scenes/procedural.h"
#include "util/input_error.h"
#include "verification/bench_suite.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const std::string kBart = (fs::path(KINRAY_SHARED_DIR) / "data" / "bart").string();

/// The flag an InputError names, empty when `f` throws nothing.
template <class F>
std::string where(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.where();
  }
  return "";
}

TEST(BenchSuite, WindowIsTheIntervalsFromTheMiddleKey) {
  const std::vector<double> keys = {0, 1, 2, 3, 4, 5, 6};
  EXPECT_EQ(suite_window(keys, 3), (std::pair<double, double>{3, 6}));
  EXPECT_EQ(suite_window(keys, 1), (std::pair<double, double>{3, 4}));
  EXPECT_EQ(suite_window(keys, 10), (std::pair<double, double>{3, 6}));  // clipped to the shot
  EXPECT_EQ(suite_window({0, 0.5}, 3), (std::pair<double, double>{0, 0.5}));
  EXPECT_EQ(suite_window({0, 1, 2, 3}, 2), (std::pair<double, double>{1, 3}));
}

TEST(BenchSuite, ScenesAreTheBuiltInsThenBart) {
  if (!fs::exists(kBart)) GTEST_SKIP() << kBart << " is absent";
  const std::vector<SuiteScene> scenes = suite_scenes({}, kBart);
  std::vector<std::string> expected = builtin_scene_names();
  expected.insert(expected.end(), {"kitchen", "robots"});
  ASSERT_EQ(scenes.size(), expected.size());
  for (size_t s = 0; s < scenes.size(); ++s) EXPECT_EQ(scenes[s].name, expected[s]);
  EXPECT_EQ(scenes.back().spec, (fs::path(kBart) / "robots" / "Robot.aff").string());
  EXPECT_EQ(suite_scenes({"orbit", "kitchen"}, kBart).size(), 2u);
}

TEST(BenchSuite, UnknownRepeatedOrAbsentScenesAreRefused) {
  EXPECT_EQ(where([] { (void)suite_scenes({"orbit", "museum"}, kBart); }), "--scenes");
  EXPECT_EQ(where([] { (void)suite_scenes({"orbit", "orbit"}, kBart); }), "--scenes");
  EXPECT_EQ(where([] { (void)suite_scenes({"orbit", "kitchen"}, "/nonexistent/bart"); }), "--bart");
  // Built-in scenes need no BART folder.
  EXPECT_EQ(suite_scenes({"orbit"}, "/nonexistent/bart").front().spec, "orbit");
}

TEST(BenchSuite, WholeAnimationOfABuiltInScene) {
  SuiteParams params;
  params.scenes = {{"static-moving", "static-moving"}};
  params.bench.base.width = 32;
  params.bench.base.height = 24;
  params.bench.base.threads = 2;
  params.bench.inbetweens = {1, 4};
  params.bench.repetitions = 1;
  params.bench.reference_frames = 3;
  params.bench.embree_modes = {{EmbreeBuild::kRefit, 1}, {EmbreeBuild::kRebuild, embree_packet_widths().back()}};
  params.intervals = 2;
  params.whole_animation = true;
  const SuiteReport report = run_suite(params);
  ASSERT_EQ(report.rows.size(), 1u);
  const SuiteRow& row = report.rows.front();
  ASSERT_EQ(row.report.points.size(), 2u);
  for (const BenchPoint& p : row.report.points) {
    EXPECT_EQ(p.sweep, "inbetweens");
    EXPECT_EQ(p.key_intervals, 2u);
    EXPECT_GE(p.frames, 2u * size_t(p.inbetweens) + 1);
    EXPECT_GT(p.events_per_key_interval(), 0);
  }
  // The events depend on the window's motion, not on the frames read out.
  EXPECT_EQ(row.report.points[0].kinetic_stats["events"],
            row.report.points[1].kinetic_stats["events"]);
  // static-moving's key grid is 24 keys per second over 2 s; the window starts at its middle key.
  EXPECT_NEAR(row.window.second - row.window.first, 2.0 / 24.0, 1e-12);
  ASSERT_TRUE(row.whole);
  EXPECT_EQ(row.whole->frames, 24u);  // a built-in scene's own schedule
  EXPECT_EQ(row.whole->embree_mode, row.report.points.front().embree_best_mode);
  EXPECT_GT(row.whole->kinetic_s, 0);
  EXPECT_GT(row.whole->embree_s, 0);
  EXPECT_EQ(row.whole->frames_compared, 3u);
  EXPECT_EQ(row.whole->mismatch_real, 0u);
  EXPECT_EQ(report.mismatch_real(), 0u);
  const nlohmann::json json = report.to_json();
  EXPECT_EQ(json["size"], "32x24");
  EXPECT_EQ(json["rows"][0]["whole_animation"]["frames"], 24);
  EXPECT_EQ(json["rows"][0]["bench"]["points"].size(), 2u);
}

}  // namespace
}  // namespace kinray
