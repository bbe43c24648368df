// `kinray ccd-queries` on every query set of ../shared/data/ccd (exact ground truth): no false
// negatives, ever.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

TEST(CcdQueriesCommand, NoFalseNegativesOnAnySharedSet) {
  const fs::path data = fs::path(KINRAY_SHARED_DIR) / "data" / "ccd";
  if (!fs::is_directory(data)) GTEST_SKIP() << "no query sets: " << data << " is absent";
  const fs::path folder = fs::temp_directory_path() / "kinray_ccd_queries_test";
  fs::create_directories(folder);
  int sets = 0;
  for (const auto& entry : fs::recursive_directory_iterator(data)) {
    if (entry.path().extension() != ".csv") continue;
    const fs::path json = folder / "result.json";
    const test::CommandRun run = test::run_kinray(
        "ccd-queries '" + entry.path().string() + "' --json '" + json.string() + "'", folder);
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json result = nlohmann::json::parse(test::read_text(json));
    EXPECT_EQ(result["false_negatives"], 0) << entry.path();
    EXPECT_GT(result["queries"].get<int>(), 0);
    EXPECT_EQ(result["true_positives"].get<int>() + result["false_positives"].get<int>() +
                  result["false_negatives"].get<int>() + result["true_negatives"].get<int>(),
              result["queries"].get<int>());
    EXPECT_GE(result["us_per_query"].get<double>(), 0.0);
    ++sets;
  }
  EXPECT_GT(sets, 0);
  fs::remove_all(folder);
}

TEST(CcdQueriesCommand, BadInputIsOneLineAndExitTwo) {
  const fs::path folder = fs::temp_directory_path() / "kinray_ccd_queries_bad";
  fs::create_directories(folder);
  const fs::path bad = folder / "queries.csv";
  std::ofstream(bad) << "1,2,3,4,5,6,0\n1,2,x,4,5,6,0\n";
  test::CommandRun run = test::run_kinray("ccd-queries '" + bad.string() + "' --type vf", folder);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("kinray: error: " + bad.string() + ":2:"), std::string::npos) << run.err;
  run = test::run_kinray("ccd-queries '" + bad.string() + "'", folder);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("--type"), std::string::npos) << run.err;
  run =
      test::run_kinray("ccd-queries '" + (folder / "missing.csv").string() + "' --type ee", folder);
  EXPECT_EQ(run.status, 2);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace kinray
