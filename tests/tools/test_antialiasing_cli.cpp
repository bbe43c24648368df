// `diff --aa exact` and `bench --aa exact` as a user runs them: the exact frames agree with the
// supersampled Embree reference within its sampling noise and the diff exits 0; the bench writes
// the "antialiasing" JSON with errors in the expected order; bad combinations are one line naming
// the flag, exit 2, nothing written.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

using AntialiasingCli = test::CommandTest;

constexpr const char* kScene = "wavy-sphere:triangles=2000 --size 32x24 --frames 2";

TEST_F(AntialiasingCli, DiffAgreesWithTheReferenceWithinItsNoise) {
  const auto run = kinray(std::string("diff ") + kScene +
                          " --aa exact --reference-samples 4096 --json " + path("d.json"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("all frames: rmse"), std::string::npos) << run.out;
  const auto summary = nlohmann::json::parse(test::read_text(path("d.json")));
  EXPECT_EQ(summary["reference_samples"], 4096);
  EXPECT_EQ(summary["aa"], "exact");
  EXPECT_EQ(summary["frames_outside"], 0);
  ASSERT_EQ(summary["per_frame"].size(), 2u);
  // What is left is the reference's noise: Embree at 1024 samples is 7.8e-5 from this reference
  // (bench --aa exact), so the reference itself is about 2.6e-5 off; 2e-4 leaves a margin of 8.
  const double rmse = summary["rmse"].get<double>();
  EXPECT_LT(rmse, 2e-4);
  // ... and it falls as the reference's does, by about (4096 / 1024)^0.75 = 2.8.
  const auto coarse =
      kinray(std::string("diff ") + kScene +
             " --aa exact --reference-samples 1024 --quiet --json " + path("c.json"));
  ASSERT_EQ(coarse.status, 0) << coarse.err;
  const auto coarse_summary = nlohmann::json::parse(test::read_text(path("c.json")));
  EXPECT_GT(coarse_summary["rmse"].get<double>(), 2 * rmse);
}

TEST_F(AntialiasingCli, BenchWritesTheAntialiasingJson) {
  const auto run = kinray(
      "bench wavy-sphere:triangles=600 --size 32x24 --aa exact --aa-sample-counts 1,4,16 "
      "--reference-samples 256 --aa-frames 3 --quiet --json " +
      path("b.json") + " --charts " + path("charts"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("embree/16"), std::string::npos) << run.out;
  // the chart of error against time per frame: a PNG image
  const std::string chart = test::read_text(path("charts/antialiasing.png"));
  ASSERT_GT(chart.size(), 8u) << run.out;
  EXPECT_EQ(chart.substr(1, 3), "PNG");
  const auto json = nlohmann::json::parse(test::read_text(path("b.json")));
  const auto& aa = json["antialiasing"];
  const auto& kinetic = aa["kinetic"];
  EXPECT_GT(kinetic["ms_per_frame"].get<double>(), 0);
  EXPECT_GE(kinetic["max_error"].get<double>(), kinetic["rmse"].get<double>());
  EXPECT_GT(kinetic["events_per_interval"].get<double>(), 0);  // the sphere's waves move edges
  const auto& embree = aa["embree"];
  ASSERT_EQ(embree.size(), 3u);
  constexpr std::array kCounts = {1, 4, 16};
  for (size_t k = 0; k < embree.size(); ++k) {
    EXPECT_EQ(embree[k]["samples"].get<int>(), kCounts[k]);
    EXPECT_GT(embree[k]["ms_per_frame"].get<double>(), 0);
    if (k > 0) {
      EXPECT_LT(embree[k]["rmse"].get<double>(), embree[k - 1]["rmse"].get<double>());
    }
  }
  EXPECT_LT(kinetic["rmse"].get<double>(), embree[0]["rmse"].get<double>());
  EXPECT_LT(kinetic["rmse"].get<double>(), embree[2]["rmse"].get<double>());
}

// With lights: render writes the exact lit frame, diff checks it against the lit reference
// (shadow rays at every sample) and exits 0, bench measures it with lights in its JSON.
TEST_F(AntialiasingCli, LightsAreRenderedDiffedAndBenched) {
  const std::string lights = " --light point:2,3,4 --light dir:-1,1,1";
  const auto render =
      kinray("render wavy-sphere:triangles=600 --size 24x16 --frames 1 --aa exact" + lights +
             " --quiet --out " + path("out") + " --stats " + path("s.json"));
  ASSERT_EQ(render.status, 0) << render.err;
  EXPECT_TRUE(fs::exists(path("out/frame_00000.png"))) << render.out;
  const auto stats = nlohmann::json::parse(test::read_text(path("s.json")));
  EXPECT_EQ(stats["lights"], 2);
  EXPECT_GT(stats["antialiasing"]["readout"]["shadow_rays"].get<double>(), 0);
  const auto diff = kinray("diff wavy-sphere:triangles=600 --size 24x16 --frames 1 --aa exact" +
                           lights + " --reference-samples 1024 --quiet --json " + path("d.json"));
  ASSERT_EQ(diff.status, 0) << diff.out << diff.err;
  const auto summary = nlohmann::json::parse(test::read_text(path("d.json")));
  EXPECT_EQ(summary["frames_outside"], 0);
  EXPECT_LT(summary["rmse"].get<double>(), 1 / std::pow(32.0, 1.5));
  const auto bench = kinray("bench wavy-sphere:triangles=600 --size 24x16 --aa exact" + lights +
                            " --aa-sample-counts 1,16 --reference-samples 256 --aa-frames 2 "
                            "--quiet --json " +
                            path("b.json"));
  ASSERT_EQ(bench.status, 0) << bench.out << bench.err;
  const auto aa = nlohmann::json::parse(test::read_text(path("b.json")))["antialiasing"];
  EXPECT_EQ(aa["lights"], 2);
  EXPECT_LT(aa["kinetic"]["rmse"].get<double>(), aa["embree"][1]["rmse"].get<double>());
}

TEST_F(AntialiasingCli, BadCombinationsNameTheFlag) {
  const std::string scene = "wavy-sphere:triangles=200 --size 16x16 --frames 2 ";
  const std::pair<std::string, std::string> cases[] = {
      {"diff " + scene + "--aa exact --shutter 0.5 --light point:0,5,0", "--aa"},
      {"diff " + scene + "--aa exact --reference-samples 3", "--reference-samples"},
      {"diff " + scene + "--aa exact --budget 3", "--budget"},
      {"bench " + scene.substr(0, scene.find(" --frames")) +
           " --aa exact --shutter 0.5 --blur-scenes orbit",
       "--blur-scenes"},
      {"bench " + scene.substr(0, scene.find(" --frames")) +
           " --aa exact --shutter 0.5 --light point:0,5,0",
       "--aa"},
      {"bench " + scene.substr(0, scene.find(" --frames")) + " --aa exact --reference-samples 3",
       "--reference-samples"},
      {"bench " + scene.substr(0, scene.find(" --frames")) + " --aa exact --aa-sample-counts 1,3",
       "--aa-sample-counts"},
  };
  for (const auto& [args, flag] : cases) {
    const auto run = kinray(args + " --json " + path("x.json"));
    EXPECT_EQ(run.status, 2) << args << ": " << run.err;
    EXPECT_EQ(run.err.find("kinray: error: " + flag), 0u) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_FALSE(fs::exists(path("x.json"))) << args;
  }
}

}  // namespace
}  // namespace kinray
