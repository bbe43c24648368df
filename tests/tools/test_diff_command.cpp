// `kinray diff` as a user runs it: exit status, table, JSON summary, report folder, bad flags.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "scenes/scene_file.h"
#include "tests/renderer/analytic_scenes.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

using test::CommandRun;

/// Runs `kinray diff ARGS` with its output captured.
CommandRun kinray_diff(const std::string& args) {
  // One folder per test: ctest runs tests in parallel processes that share TempDir().
  const ::testing::TestInfo* test = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path folder = fs::path(::testing::TempDir()) /
                          ("kinray_diff_command_" + std::string(test->test_suite_name()) + "_" +
                           test->name() + "_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  return test::run_kinray("diff " + args, folder);
}

/// A fresh, empty scratch folder for one test.
fs::path scratch(const std::string& name) {
  const fs::path folder =
      fs::path(::testing::TempDir()) / ("kinray_diff_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

/// A scene where GL's fill rule and the exact sign rule disagree along a whole row: a triangle
/// whose horizontal bottom edge lies 1.9/1024 pixel above the centres of GL row 40 (image row 23
/// of 64). The exact rule leaves the row out; llvmpipe snaps vertices to 1/256 pixel, which puts
/// the edge on the centres, and its fill rule takes them: 64 real mismatches per frame, far more
/// than the default budget (0.1% of 4096 pixels) and far outside the tie zone.
std::string fill_rule_scene(const fs::path& folder) {
  const double edge_y = 2.0 * (40 + 0.5 + 1.9 / 1024) / 64 - 1, z = 2;
  const Object sliver = test::camera_space_object(
      "sliver", {{0, 1, 2}},
      {{Vec3(-1.5 * z, edge_y * z, z), Vec3(1.5 * z, edge_y * z, z), Vec3(0, 3 * z, z)}});
  const std::string path = (folder / "fill_rule.json").string();
  save_scene_file(test::analytic_scene({sliver}), path);
  return path;
}

TEST(DiffCommand, OsmesaAgainstEmbreeWithinBudgetWritesTableAndJson) {
#ifndef KINRAY_WITH_OSMESA
  GTEST_SKIP() << "built without OSMesa (KINRAY_WITH_OSMESA=OFF)";
#endif
  const fs::path folder = scratch("within");
  const CommandRun run = kinray_diff(
      "static-moving:triangles=2000 --backend osmesa --against embree --size 96x64 "
      "--frames 3 -q --json " +
      (folder / "summary.json").string() + " --report " + (folder / "report").string());
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json json = read_json(folder / "summary.json");
  EXPECT_EQ(json["frames"], 3);
  EXPECT_EQ(json["pixels"], 3 * 96 * 64);
  EXPECT_EQ(json["mismatch_real"], 0);
  EXPECT_EQ(json["tested"], "osmesa");
  EXPECT_EQ(json["reference"], "embree");
  ASSERT_EQ(json["per_frame"].size(), 3u);
  EXPECT_EQ(read_json(folder / "report" / "summary.json"), json);
  // Frames with ties have their heat map in the report.
  for (const auto& line : json["per_frame"]) {
    if (line["mismatch_tie"].get<int>() > 0) {
      EXPECT_TRUE(fs::exists(line["heat_map"].get<std::string>()));
    }
  }
}

TEST(DiffCommand, DefaultsToTheKineticBackendAgainstEmbree) {
  const fs::path folder = scratch("default");
  const CommandRun run =
      kinray_diff("static-moving:triangles=1000 --size 64x48 --frames 3 -q --json " +
                  (folder / "summary.json").string());
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json json = read_json(folder / "summary.json");
  EXPECT_EQ(json["tested"], "kinetic");
  EXPECT_EQ(json["reference"], "embree");
  EXPECT_EQ(json["frames"], 3);
  EXPECT_EQ(json["mismatch_real"], 0);
}

TEST(DiffCommand, PrintsTheTable) {
  const CommandRun run = kinray_diff(
      "static-moving:triangles=2000 --backend embree --against embree --size 48x32 --frames 2");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("embree against embree"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("total: 2 frames, 3072 pixels, 0 real mismatches"), std::string::npos)
      << run.out;
  EXPECT_NE(run.out.find("budget: 0 per frame, met"), std::string::npos) << run.out;
}

TEST(DiffCommand, ExceededBudgetFailsAndLeavesTheEvidence) {
#ifndef KINRAY_WITH_OSMESA
  GTEST_SKIP() << "built without OSMesa (KINRAY_WITH_OSMESA=OFF)";
#endif
  const fs::path folder = scratch("exceeded");
  const std::string scene = fill_rule_scene(folder);
  const std::string common =
      scene + " --backend embree --against osmesa --size 64x64 --frames 2 -q";
  const CommandRun run = kinray_diff(common + " --json " + (folder / "summary.json").string() +
                                     " --report " + (folder / "report").string());
  EXPECT_EQ(run.status, 1) << run.err;
  EXPECT_NE(run.err.find("exceed the budget"), std::string::npos) << run.err;
  const nlohmann::json json = read_json(folder / "summary.json");
  EXPECT_GE(json["mismatch_real"].get<int>(), 2 * 32);
  EXPECT_TRUE(fs::exists(folder / "report" / "diff_00000.png"));
  EXPECT_TRUE(fs::exists(folder / "report" / "tested_00000.png"));
  EXPECT_TRUE(fs::exists(folder / "report" / "reference_00000.png"));
  // A budget that covers the row (2% of 4096 = 81 pixels per frame) passes; an explicit 0 fails.
  EXPECT_EQ(kinray_diff(common + " --budget 2%").status, 0);
  EXPECT_EQ(kinray_diff(common + " --budget 0").status, 1);
  EXPECT_EQ(kinray_diff(common + " --budget 64").status,
            json["per_frame"][0]["mismatch_real"].get<int>() <= 64 ? 0 : 1);
}

TEST(DiffCommand, BadFlagsFailWithOneLineAndWriteNothing) {
  const fs::path folder = scratch("bad");
  const std::string outputs =
      " --json " + (folder / "summary.json").string() + " --report " + (folder / "report").string();
  for (const char* args :
       {"static-moving --backend embree --against osmesa --budget -1",
        "static-moving --backend embree --budget 1.5",
        "static-moving --backend embree --budget 101%",
        "static-moving --backend embree --budget lots",
        "static-moving --backend embree --against kinetic", "static-moving --backend nonsense",
        "no-such-scene --backend embree", "static-moving --backend embree --size 0x5",
        "static-moving --backend embree --frames 3 --fps 2"}) {
    const CommandRun run = kinray_diff(std::string(args) + outputs);
    EXPECT_EQ(run.status, 2) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_EQ(run.err.rfind("kinray: error: ", 0), 0u) << args << ": " << run.err;
    EXPECT_FALSE(fs::exists(folder / "summary.json")) << args;
    EXPECT_FALSE(fs::exists(folder / "report")) << args;
  }
}

}  // namespace
}  // namespace kinray
