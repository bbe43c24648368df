// `render`, `diff` and `bench` with `--aa exact --shutter S` as a user runs them: the space-time
// box filter renders, agrees with Embree's (x, y, t) samples within the reference's noise (diff
// exits 0), and the bench writes the "antialiasing" JSON with the shutter recorded; the sampling
// peer's `--aa-samples N --shutter S` renders too.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

using ExactShutterCli = test::CommandTest;

constexpr const char* kScene = "orbit:triangles=600 --size 24x24 --frames 2 --shutter 0.5";

TEST_F(ExactShutterCli, RendersBothPeersWithStats) {
  const auto exact = kinray(std::string("render ") + kScene + " --aa exact --quiet --out " +
                            path("exact") + " --stats " + path("exact.json"));
  ASSERT_EQ(exact.status, 0) << exact.err;
  EXPECT_TRUE(fs::exists(path("exact") + "/frame_00001.png"));
  const auto stats = nlohmann::json::parse(test::read_text(path("exact.json")));
  EXPECT_EQ(stats["aa"], "exact");
  EXPECT_EQ(stats["shutter"], 0.5);
  const auto& shutter = stats["antialiasing"]["shutter"];
  EXPECT_EQ(shutter["windows"], 2);
  EXPECT_EQ(shutter["order"], 4);
  // Every pixel of both windows is read out at least once; orbit's moving pixels four times a
  // piece.
  EXPECT_GE(shutter["readouts"].get<int>(), 2 * 24 * 24);
  EXPECT_GT(shutter["readouts"].get<int>(), shutter["pieces"].get<int>());
  EXPECT_GT(shutter["changes"].get<int>(), 0);
  EXPECT_EQ(shutter["rebuilds"], 0);  // a regular schedule's windows do not overlap
  const auto sampled = kinray(std::string("render ") + kScene +
                              " --backend embree --aa-samples 16 --quiet --out " + path("s"));
  ASSERT_EQ(sampled.status, 0) << sampled.err;
  EXPECT_TRUE(fs::exists(path("s") + "/frame_00001.png"));
  // The sampling peer shades its (x, y, t) samples with lights and shadow rays too.
  const auto lit =
      kinray(std::string("render ") + kScene +
             " --backend embree --aa-samples 4 --light point:0,5,0 --quiet --out " + path("lit"));
  ASSERT_EQ(lit.status, 0) << lit.err;
  EXPECT_TRUE(fs::exists(path("lit") + "/frame_00001.png"));
}

TEST_F(ExactShutterCli, DiffAgreesWithTheSpaceTimeReference) {
  const auto run = kinray(std::string("diff ") + kScene +
                          " --aa exact --reference-samples 1024 --json " + path("d.json"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("in (x, y, t)"), std::string::npos) << run.out;
  const auto summary = nlohmann::json::parse(test::read_text(path("d.json")));
  EXPECT_EQ(summary["shutter"], 0.5);
  EXPECT_EQ(summary["frames_outside"], 0);
  // Far below the tolerance (5.5e-3 at 1024 samples): measured 1e-3, the reference's noise.
  EXPECT_LT(summary["rmse"].get<double>(), 2e-3);
}

TEST_F(ExactShutterCli, BenchRecordsTheShutter) {
  const auto run = kinray(
      "bench orbit:triangles=600 --size 24x24 --aa exact --shutter 0.5 --aa-sample-counts 1,16 "
      "--reference-samples 256 --aa-frames 3 --quiet --json " +
      path("b.json"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("under the shutter 0.5"), std::string::npos) << run.out;
  const auto json = nlohmann::json::parse(test::read_text(path("b.json")));
  const auto& aa = json["antialiasing"];
  EXPECT_EQ(aa["shutter"], 0.5);
  EXPECT_GT(aa["kinetic"]["ms_per_frame"].get<double>(), 0);
  ASSERT_EQ(aa["embree"].size(), 2u);
  // The exact frames beat the sampled ones at 16 samples in (x, y, t).
  EXPECT_LT(aa["kinetic"]["rmse"].get<double>(), aa["embree"][1]["rmse"].get<double>());
}

}  // namespace
}  // namespace kinray
