// kinray bench --suite as a user runs it: a built-in scene and BART's kitchen in one table whose
// rows are consistent (events, speedups against the fastest measured Embree mode, break-even,
// no real mismatch), and flags that do not combine with --suite refused in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/scenes/aff_file_facts.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const std::string kBart = (fs::path(KINRAY_SHARED_DIR) / "data" / "bart").string();

class BenchSuiteCommand : public test::CommandTest {};

/// One row's in-between points are consistent: the speedup is the fastest peer over kinetic.
void check_points(const nlohmann::json& row) {
  const nlohmann::json& points = row["bench"]["points"];
  ASSERT_EQ(points.size(), 3u);
  std::vector<int> ks;
  bool kinetic_wins_somewhere = false;
  for (const nlohmann::json& p : points) {
    ks.push_back(p["inbetweens"].get<int>());
    EXPECT_GT(p["kinetic_events_per_key_interval"].get<double>(), 0);
    const double kinetic = p["kinetic_ms_per_frame"].get<double>();
    EXPECT_GT(kinetic, 0);
    double fastest = 1e300;
    std::string fastest_mode;
    for (const nlohmann::json& peer : p["embree"]) {
      EXPECT_GT(peer["ms_per_frame"].get<double>(), 0);
      EXPECT_EQ(peer["mismatch_real"], 0);
      if (peer["ms_per_frame"].get<double>() < fastest) {
        fastest = peer["ms_per_frame"].get<double>();
        fastest_mode = peer["mode"].get<std::string>();
      }
    }
    EXPECT_EQ(p["embree_best_mode"], fastest_mode);
    EXPECT_DOUBLE_EQ(p["embree_best_ms_per_frame"].get<double>(), fastest);
    const double speedup = row["speedup_vs_best_embree"][std::to_string(ks.back())].get<double>();
    EXPECT_GT(speedup, 0);
    EXPECT_DOUBLE_EQ(speedup, fastest / kinetic);
    kinetic_wins_somewhere |= speedup >= 1;
    EXPECT_EQ(p["mismatch_real"], 0);
    EXPECT_GT(p["pixels_compared"].get<double>(), 0);
  }
  EXPECT_EQ(ks, (std::vector<int>{1, 16, 128}));
  // The events per interval of the row are those of the window, whatever the frames read out.
  EXPECT_EQ(row["events_per_key_interval"], points[0]["kinetic_events_per_key_interval"]);
  EXPECT_EQ(points[0]["kinetic_stats"]["events"], points[2]["kinetic_stats"]["events"]);
  // A break-even exactly when kinetic is as fast at some measured K, and within the measured Ks.
  EXPECT_EQ(row["break_even_inbetweens"].is_null(), !kinetic_wins_somewhere);
  if (!row["break_even_inbetweens"].is_null()) {
    EXPECT_GE(row["break_even_inbetweens"].get<double>(), 1);
    EXPECT_LE(row["break_even_inbetweens"].get<double>(), 128);
  }
}

TEST_F(BenchSuiteCommand, TableOfABuiltInSceneAndTheKitchen) {
  if (!fs::exists(kBart)) GTEST_SKIP() << kBart << " is absent";
  const test::CommandRun run = kinray(
      "bench --suite --scenes static-moving,kitchen --bart '" + kBart +
      "' --size 32x24 --keyrate 4 --intervals 1 --repetitions 1 --reference-frames 2 -q --json '" +
      path("suite.json") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("\nstatic-moving "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("\nkitchen "), std::string::npos) << run.out;
  const nlohmann::json json = nlohmann::json::parse(test::read_text(path("suite.json")));
  const nlohmann::json& suite = json["suite"];
  EXPECT_EQ(suite["size"], "32x24");
  ASSERT_EQ(suite["rows"].size(), 2u);
  EXPECT_EQ(suite["rows"][0]["scene"], "static-moving");
  EXPECT_EQ(suite["rows"][1]["scene"], "kitchen");
  EXPECT_EQ(suite["rows"][1]["triangles"],
            test::aff_triangle_count(fs::path(kBart) / "kitchen" / "kitchen.aff"));
  // --keyrate 4 applies to BART's file: one interval of 0.25 s from the middle key (t = 10 s).
  EXPECT_EQ(suite["rows"][1]["window_s"], (nlohmann::json{10.0, 10.25}));
  for (const nlohmann::json& row : suite["rows"]) {
    SCOPED_TRACE(row["scene"].get<std::string>());
    EXPECT_EQ(row["mismatch_real"], 0);
    EXPECT_FALSE(row.contains("whole_animation"));  // BART's measure only with --whole-animation
    check_points(row);
  }
}

TEST_F(BenchSuiteCommand, FlagsThatDoNotCombineAreRefused) {
  const std::string suite =
      "bench --suite --scenes orbit --size 16x16 --json '" + path("s.json") + "' ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"bench --suite orbit", "SCENE: does not combine with --suite"},
      {suite + "--time 0:1", "--time: does not combine with --suite"},
      {suite + "--triangles 100,200", "--triangles: does not combine with --suite"},
      {suite + "--csv '" + path("s.csv") + "'", "--csv: does not combine with --suite"},
      {suite + "--structure aabb", "--structure: does not combine with --suite"},
      {suite + "--shutter 0.5", "--shutter: does not combine with --suite"},
      {suite + "--keyrate 4", "--keyrate: applies to BART's scenes, and none is in --scenes"},
      {suite + "--intervals 0", "--intervals: must lie in 1..1000"},
      {"bench --suite --scenes orbit,museum", "--scenes: no suite scene 'museum'"},
      {"bench --suite --scenes kitchen --bart '" + path("nothing") + "'",
       "--bart: BART's kitchen is not at"},
      {"bench orbit --scenes orbit", "--scenes: applies to --suite only"},
      {"bench orbit --whole-animation", "--whole-animation: applies to --suite only"},
  };
  for (const auto& [args, line] : cases) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind("kinray: error: " + line, 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_TRUE(run.out.empty()) << run.out;
  }
  EXPECT_FALSE(fs::exists(path("s.json")));
  EXPECT_FALSE(fs::exists(path("s.csv")));
}

TEST_F(BenchSuiteCommand, BenchOfABartFileAtAnotherSize) {
  // bench used to give the kinetic backend BART's own 800 x 600 and Embree --size.
  if (!fs::exists(kBart)) GTEST_SKIP() << kBart << " is absent";
  const test::CommandRun run =
      kinray("bench '" + kBart +
             "/kitchen/kitchen.aff' --keyrate 4 --time 10:10.25 --inbetweens 1 --size 32x24 "
             "--repetitions 1 --reference-frames 1 --embree-modes refit/1 -q");
  EXPECT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("32x24"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace kinray
