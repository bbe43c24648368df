// What `kinray render` tells its user: the summary's total time (loading included) and kinetic
// event count, and no kinetic-versus-Embree warning on a short render.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <regex>
#include <string>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

class CliRenderFeedback : public test::CommandTest {};

TEST_F(CliRenderFeedback, SummaryGivesTotalTimeWithLoadingAndTheKineticEventCount) {
  const test::CommandRun run =
      kinray("render wavy-sphere:triangles=600 --size 64x48 --frames 6 --out '" + path("frames") +
             "' --stats '" + path("stats.json") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  // A short quick render: no forecast warning, nothing at all on stderr (not a terminal).
  EXPECT_EQ(run.err, "");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(
      run.out, match,
      std::regex(
          R"(with kinetic in ([0-9.]+) s \(loading ([0-9.]+) s, ([0-9]+) kinetic events\))")))
      << run.out;
  const nlohmann::json stats = nlohmann::json::parse(test::read_text(path("stats.json")));
  EXPECT_EQ(std::stoull(match[3].str()), stats["events"]["total"].get<uint64_t>());
  EXPECT_GT(stats["events"]["total"].get<uint64_t>(), 0u);  // a moving sphere has events
  // The total covers loading: it is at least the load time, and matches --stats to the printed
  // precision.
  EXPECT_GE(std::stod(match[1].str()) + 0.005, std::stod(match[2].str()));
  EXPECT_NEAR(std::stod(match[1].str()), stats["time_s"]["total"].get<double>(), 0.006);
  EXPECT_NEAR(std::stod(match[2].str()), stats["time_s"]["load"].get<double>(), 0.006);
}

TEST_F(CliRenderFeedback, EmbreeSummaryHasNoKineticEvents) {
  const test::CommandRun run = kinray(
      "render wavy-sphere:triangles=600 --size 64x48 --frames 3 "
      "--backend embree --out '" +
      path("frames") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("with embree in "), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("(loading "), std::string::npos) << run.out;
  EXPECT_EQ(run.out.find("kinetic events"), std::string::npos) << run.out;
}

}  // namespace
}  // namespace kinray
