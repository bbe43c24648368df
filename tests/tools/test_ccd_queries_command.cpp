// `kinray ccd-queries` on every query set of ../shared/data/ccd (exact ground truth): no false
// negatives, ever.
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
  int sets = 0, queries = 0;
  for (const auto& entry : fs::recursive_directory_iterator(data)) {
    if (entry.path().extension() != ".csv") continue;
    SCOPED_TRACE(entry.path().string());
    const fs::path json = folder / "result.json";
    const test::CommandRun run = test::run_kinray(
        "ccd-queries '" + entry.path().string() + "' --json '" + json.string() + "'", folder);
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json result = nlohmann::json::parse(test::read_text(json));
    const GroundTruth truth = ground_truth(entry.path());
    // exact: neither a missed contact nor a contact that is not one
    EXPECT_EQ(result["queries"].get<int>(), truth.queries);
    EXPECT_EQ(result["true_positives"].get<int>(), truth.contacts);
    EXPECT_EQ(result["true_negatives"].get<int>(), truth.queries - truth.contacts);
    EXPECT_EQ(result["false_negatives"], 0);
    EXPECT_EQ(result["false_positives"], 0);
    EXPECT_GE(result["us_per_query"].get<double>(), 0.0);
    ++sets;
    queries += truth.queries;
  }
  // ../shared/data/ccd holds 28 sets of Sample-Queries, 3,324 queries in all
  EXPECT_EQ(sets, 28);
  EXPECT_EQ(queries, 3324);
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
  fs::remove_all(folder);
}

}  // namespace
}  // namespace kinray
