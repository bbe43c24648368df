// `kinray ccd-queries` on every query set of ../shared/data/ccd (exact ground truth): no false
// negatives and no false positives, on any number of threads.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include <unistd.h>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// The queries of a set and how many of them the ground truth calls a contact, counted from the
/// file itself (8 rows a query, the truth in the last column of its first row).
struct GroundTruth {
  int queries = 0, contacts = 0;
};

GroundTruth ground_truth(const fs::path& file) {
  std::ifstream in(file);
  GroundTruth truth;
  int row = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line == "\r") continue;
    if (row++ % 8 != 0) continue;
    ++truth.queries;
    const size_t comma = line.rfind(',');
    truth.contacts += line.compare(comma + 1, 1, "1") == 0;
  }
  return truth;
}

TEST(CcdQueriesCommand, EveryQueryOfEverySharedSetAnsweredAsItsGroundTruth) {
  const fs::path data = fs::path(KINRAY_SHARED_DIR) / "data" / "ccd";
  if (!fs::is_directory(data)) GTEST_SKIP() << "no query sets: " << data << " is absent";
  const fs::path folder = fs::temp_directory_path() / ("kinray_ccd_queries_test_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  // the whole folder in one run, one row per set; then again on two threads
  nlohmann::json by_threads[2];
  for (int threads : {1, 2}) {
    const fs::path json = folder / "result.json";
    const test::CommandRun run = test::run_kinray(
        "ccd-queries '" + data.string() + "' --threads " + std::to_string(threads) +
            " --repetitions 1 --json '" + json.string() + "'",
        folder);
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json result = nlohmann::json::parse(test::read_text(json));
    by_threads[threads - 1] = result;
    int queries = 0;
    for (const nlohmann::json& set : result["sets"]) {
      const fs::path file = set["file"].get<std::string>();
      SCOPED_TRACE(file.string());
      const GroundTruth truth = ground_truth(file);
      // exact: neither a missed contact nor a contact that is not one
      EXPECT_EQ(set["queries"].get<int>(), truth.queries);
      EXPECT_EQ(set["true_positives"].get<int>(), truth.contacts);
      EXPECT_EQ(set["true_negatives"].get<int>(), truth.queries - truth.contacts);
      EXPECT_EQ(set["false_negatives"], 0);
      EXPECT_EQ(set["false_positives"], 0);
      EXPECT_GE(set["us_per_query"].get<double>(), 0.0);
      // the table's row: "| erleben-wedges data_0_1 | ee | 125 | ..."
      const std::string row = "| " + set["set"].get<std::string>() + " | " +
                              set["type"].get<std::string>() + " | " +
                              std::to_string(truth.queries) + " | ";
      EXPECT_NE(run.out.find(row), std::string::npos) << run.out;
      queries += truth.queries;
    }
    // ../shared/data/ccd holds 28 sets of Sample-Queries, 3,324 queries in all
    EXPECT_EQ(result["sets"].size(), 28u);
    EXPECT_EQ(queries, 3324);
    EXPECT_EQ(result["queries"], 3324);
    EXPECT_EQ(result["false_negatives"], 0);
    EXPECT_EQ(result["false_positives"], 0);
    EXPECT_NE(run.out.find("| all | | 3324 | "), std::string::npos) << run.out;
  }
  // threads change the time, not one answer nor how it was decided
  for (size_t i = 0; i < by_threads[0]["sets"].size(); ++i)
    for (const char* key : {"true_positives", "false_positives", "exact_decisions", "stats"})
      EXPECT_EQ(by_threads[0]["sets"][i][key], by_threads[1]["sets"][i][key]) << key;
  fs::remove_all(folder);
}

TEST(CcdQueriesCommand, BadInputIsOneLineAndExitTwo) {
  const fs::path folder = fs::temp_directory_path() / ("kinray_ccd_queries_bad_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path bad = folder / "queries.csv";
  std::ofstream(bad) << "1,2,3,4,5,6,0\n1,2,x,4,5,6,0\n";
  test::CommandRun run = test::run_kinray("ccd-queries '" + bad.string() + "' --type vf", folder);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("kinray: error: " + bad.string() + ":2:"), std::string::npos) << run.err;
  // a valid file whose path names neither vertex-face nor edge-edge needs --type
  const fs::path untyped = folder / "queries_untyped.csv";
  {
    std::ofstream file(untyped);
    for (int row = 0; row < 8; ++row) file << "0,1,0,1," << row << ",1,0\n";
  }
  run = test::run_kinray("ccd-queries '" + untyped.string() + "'", folder);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("--type"), std::string::npos) << run.err;
  run =
      test::run_kinray("ccd-queries '" + (folder / "missing.csv").string() + "' --type ee", folder);
  EXPECT_EQ(run.status, 2);
  fs::remove_all(folder);
}

// A coordinate beyond the doubles' range (a 401-digit integer) is an exact rational like any
// other: it takes the exact test (GMP stopped the process with SIGFPE when the reader asked it for
// the rational of the infinite double). The vertex crosses the plane z = 0 of the still unit
// triangle at x = 1e400, far outside it: no contact, so the truth column's 1 counts as a false
// negative. A vertex at a coordinate that is no double, through the triangle, is a contact.
TEST(CcdQueriesCommand, ACoordinateBeyondTheDoublesRangeIsDecidedExactly) {
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_ccd_queries_big_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  const fs::path file = folder / "queries.csv";
  {
    const std::string far = "1" + std::string(400, '0');
    const char* triangle = "0,1,0,1,0,1,1\n1,1,0,1,0,1,1\n0,1,1,1,0,1,1\n";
    // (10^400 + 1) / (4 10^400): just above 1/4, and no double.
    const std::string quarter = "1" + std::string(399, '0') + "1,4" + std::string(400, '0');
    std::ofstream(file) << far << ",1,0,1,1,1,1\n"
                        << triangle << far << ",1,0,1,-1,1,1\n"
                        << triangle << quarter << "," << quarter << ",1,1,1\n"
                        << triangle << quarter << "," << quarter << ",-1,1,1\n"
                        << triangle;
  }
  const fs::path json = folder / "result.json";
  const test::CommandRun run = test::run_kinray(
      "ccd-queries '" + file.string() + "' --type vf --json '" + json.string() + "'", folder);
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json result = nlohmann::json::parse(test::read_text(json));
  EXPECT_EQ(result["queries"], 2);
  EXPECT_EQ(result["false_negatives"], 1);  // the far vertex: no contact, though truth says 1
  EXPECT_EQ(result["true_positives"], 1);   // the vertex near (1/4, 1/4) goes through the face
  EXPECT_EQ(result["exact_decisions"], 0);  // neither motion is doubles: the exact path alone
  EXPECT_EQ(result["rational_queries"], 2);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace kinray
