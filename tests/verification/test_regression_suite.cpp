// The image regression suite: every case against the references stored in images/regression/
// (ID buffers exact up to ties, shaded images by PSNR and maximum error) and against Embree, with
// the kinetic backend's audit on. Then the suite itself: references are written only by an update,
// round-trip exactly, and a corrupted reference frame (IDs or colours) is caught with its diff
// images written; missing or stale references fail with a message that says how to record them;
// `kinray regress` as a user runs it. Tests never write into images/regression.

#include <algorithm>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "renderer/frame.h"
#include "renderer/output/image_io.h"
#include "tests/tools/kinray_process.h"
#include "util/warning.h"
#include "verification/regression_suite.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const fs::path kReferences = fs::path(KINRAY_SOURCE_DIR) / "images" / "regression";

/// A fresh, empty scratch folder for one test.
fs::path scratch(const std::string& name) {
  const fs::path folder = fs::path(::testing::TempDir()) / ("kinray_regression_" + name);
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

RegressionConfig test_config(const fs::path& references, const fs::path& report) {
  RegressionConfig config;
  config.references = references.string();
  config.report = report.string();
  config.shared_models = (fs::path(KINRAY_SHARED_DIR) / "data" / "models").string();
  config.threads = 2;
  return config;
}

class Cases : public ::testing::TestWithParam<RegressionCase> {};

TEST_P(Cases, MatchesItsReferencesAndEmbree) {
  const RegressionCase& c = GetParam();
  const fs::path report = fs::path(::testing::TempDir()) / "kinray_regression_report";
  const ScopedWarningSink quiet([](const std::string&) {});  // model import warnings
  const RegressionCaseResult result = run_regression_case(c, test_config(kReferences, report));
  if (result.status == RegressionStatus::kSkipped) GTEST_SKIP() << result.message;
  EXPECT_EQ(result.status, RegressionStatus::kPassed) << result.message;
  ASSERT_EQ(result.frames.size(), size_t(c.frames));
  size_t covered = 0;
  for (const RegressionFrameResult& f : result.frames) {
    EXPECT_EQ(f.reference_real, 0u) << "frame " << f.frame;
    EXPECT_EQ(f.embree_real, 0u) << "frame " << f.frame;
    covered += f.covered;
  }
  EXPECT_GT(covered, 0u) << "the case shows nothing";
}

INSTANTIATE_TEST_SUITE_P(RegressionSuite, Cases, ::testing::ValuesIn(regression_cases()),
                         [](const ::testing::TestParamInfo<RegressionCase>& param) {
                           std::string name = param.param.name;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(RegressionSuite, EveryCaseHasSmallReferences) {
  uintmax_t bytes = 0;
  for (const RegressionCase& c : regression_cases()) {
    const fs::path folder = kReferences / c.name;
    ASSERT_TRUE(fs::is_regular_file(folder / "case.json")) << folder;
    for (int f = 0; f < c.frames; ++f) {
      char id[32], color[32];
      std::snprintf(id, sizeof id, "id_%05d.png", f);
      std::snprintf(color, sizeof color, "color_%05d.png", f);
      ASSERT_TRUE(fs::is_regular_file(folder / id)) << folder / id;
      ASSERT_TRUE(fs::is_regular_file(folder / color)) << folder / color;
    }
    for (const auto& entry : fs::directory_iterator(folder)) bytes += entry.file_size();
  }
  EXPECT_LT(bytes, 5u << 20) << "the references must stay small";
}

/// A small case of its own, so that the suite's machinery is tested without the stored references.
RegressionCase small_case() {
  RegressionCase c;
  c.name = "small-wavy-sphere";
  c.scene = "wavy-sphere:triangles=300,duration=0.5,keyrate=8";
  c.width = 48;
  c.height = 36;
  c.frames = 3;
  return c;
}

/// Sets a block of `radius` pixels around (ci, cj) of an ID buffer file to the background.
size_t erase_block(const fs::path& path, int ci, int cj, int radius) {
  Frame frame;
  read_id_png(path.string(), frame);
  size_t erased = 0;
  for (int j = cj - radius; j <= cj + radius; ++j)
    for (int i = ci - radius; i <= ci + radius; ++i) {
      const size_t p = frame.index(i, j);
      if (frame.object[p] == kNoHit) continue;
      frame.object[p] = frame.prim[p] = kNoHit;
      ++erased;
    }
  write_id_png(path.string(), frame);
  return erased;
}

TEST(RegressionSuite, UpdateRoundTripsAndCorruptedFramesAreCaughtWithDiffImages) {
  const fs::path folder = scratch("corrupt");
  const RegressionCase c = small_case();
  RegressionConfig config = test_config(folder / "references", folder / "report");

  // Without references the case fails, and says how to record them.
  RegressionCaseResult result = run_regression_case(c, config);
  EXPECT_EQ(result.status, RegressionStatus::kFailed);
  EXPECT_NE(result.message.find("--update-references"), std::string::npos) << result.message;
  EXPECT_FALSE(fs::exists(folder / "references"));

  config.update = true;
  result = run_regression_case(c, config);
  ASSERT_EQ(result.status, RegressionStatus::kUpdated) << result.message;
  const fs::path refs = folder / "references" / c.name;
  for (const char* file : {"case.json", "id_00000.png", "color_00000.png", "id_00002.png", "color_00002.png"})
    EXPECT_TRUE(fs::is_regular_file(refs / file)) << file;

  config.update = false;
  result = run_regression_case(c, config);
  ASSERT_EQ(result.status, RegressionStatus::kPassed) << result.message;
  for (const RegressionFrameResult& f : result.frames) {
    EXPECT_EQ(f.reference_real + f.reference_ties, 0u);
    EXPECT_FALSE(f.psnr_db.has_value()) << "identical colours";
    EXPECT_EQ(f.max_code_error, 0);
  }
  EXPECT_FALSE(fs::exists(folder / "report" / c.name)) << "a passing case writes no report";

  // Frame 1: a block of the sphere's interior erased from the reference IDs. Frame 2: the
  // reference colours brightened by 12 codes in a block, IDs untouched.
  const size_t erased = erase_block(refs / "id_00001.png", 24, 18, 3);
  ASSERT_GT(erased, 30u);
  cv::Mat color = cv::imread((refs / "color_00002.png").string(), cv::IMREAD_COLOR);
  for (int j = 10; j < 20; ++j)
    for (int i = 10; i < 20; ++i)
      for (int k = 0; k < 3; ++k) color.at<cv::Vec3b>(j, i)[k] = cv::saturate_cast<uint8_t>(color.at<cv::Vec3b>(j, i)[k] + 12);
  cv::imwrite((refs / "color_00002.png").string(), color);

  result = run_regression_case(c, config);
  ASSERT_EQ(result.status, RegressionStatus::kFailed);
  ASSERT_EQ(result.frames.size(), 3u);
  EXPECT_TRUE(result.frames[0].passed());
  EXPECT_GE(result.frames[1].reference_real, erased / 2);
  EXPECT_FALSE(result.frames[1].passed());
  EXPECT_EQ(result.frames[2].reference_real, 0u);
  EXPECT_GE(result.frames[2].max_code_error, 11);
  EXPECT_FALSE(result.frames[2].passed());
  EXPECT_NE(result.message.find("frame 1"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("frame 2"), std::string::npos) << result.message;
  const fs::path report = folder / "report" / c.name;
  EXPECT_EQ(result.report_folder, report.string());
  EXPECT_NE(result.message.find(report.string()), std::string::npos) << "the failure names its report";

  // The heat map of frame 1 is red where the reference was erased.
  const cv::Mat heat = cv::imread((report / "reference_diff_00001.png").string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(heat.empty());
  size_t red = 0;
  for (int j = 15; j <= 21; ++j)
    for (int i = 21; i <= 27; ++i) red += heat.at<cv::Vec3b>(j, i) == cv::Vec3b(0, 0, 255);
  EXPECT_EQ(red, result.frames[1].reference_real);
  for (const char* file : {"kinetic_00001.png", "kinetic_id_00001.png", "reference_00001.png", "embree_00001.png",
                           "embree_diff_00001.png", "color_error_00002.png", "reference_00002.png"})
    EXPECT_TRUE(fs::is_regular_file(report / file)) << file;
  EXPECT_FALSE(fs::exists(report / "kinetic_00000.png")) << "frames that pass are not written";
  const cv::Mat error = cv::imread((report / "color_error_00002.png").string(), cv::IMREAD_GRAYSCALE);
  ASSERT_FALSE(error.empty());
  EXPECT_GE(error.at<uint8_t>(15, 15), 8 * 11);
  EXPECT_EQ(error.at<uint8_t>(30, 40), 0);
}

TEST(RegressionSuite, ReferencesOfAnotherVersionOfTheCaseAreStale) {
  const fs::path folder = scratch("stale");
  RegressionCase c = small_case();
  c.frames = 2;
  RegressionConfig config = test_config(folder / "references", folder / "report");
  config.update = true;
  ASSERT_EQ(run_regression_case(c, config).status, RegressionStatus::kUpdated);
  config.update = false;
  c.frames = 3;
  RegressionCaseResult result = run_regression_case(c, config);
  EXPECT_EQ(result.status, RegressionStatus::kFailed);
  EXPECT_NE(result.message.find("another version of the case"), std::string::npos) << result.message;
  EXPECT_TRUE(result.frames.empty()) << "nothing is compared against stale references";
  c.frames = 2;
  c.scene = "wavy-sphere:triangles=400,duration=0.5,keyrate=8";
  result = run_regression_case(c, config);
  EXPECT_EQ(result.status, RegressionStatus::kFailed);
  EXPECT_NE(result.message.find("'scene'"), std::string::npos) << result.message;
}

TEST(RegressionSuite, MissingModelIsSkippedAndAnUnknownCaseIsAnInputError) {
  RegressionCase c;
  c.name = "missing";
  c.scene = "no/such/model.gltf";
  c.root = ModelRoot::kTestModels;
  const RegressionCaseResult result = run_regression_case(c, test_config(scratch("missing"), ""));
  EXPECT_EQ(result.status, RegressionStatus::kSkipped);
  EXPECT_NE(result.message.find("no/such/model.gltf"), std::string::npos);
  EXPECT_THROW((void)find_regression_case("no-such-case"), std::exception);
  EXPECT_EQ(find_regression_case("cloth").name, "cloth");
}

TEST(RegressCommand, UpdatesThenPassesThenCatchesACorruptedReference) {
  const fs::path folder = scratch("command");
  const std::string refs = (folder / "refs").string(), report = (folder / "report").string();
  const std::string common = " --case wavy-sphere --threads 2 --references " + refs + " --report " + report;
  test::CommandRun run = test::run_kinray("regress --update-references" + common, folder);
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("updated"), std::string::npos) << run.out;
  run = test::run_kinray("regress" + common, folder);
  EXPECT_EQ(run.status, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("passed"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("1 passed"), std::string::npos) << run.out;

  erase_block(folder / "refs" / "wavy-sphere" / "id_00000.png", 48, 36, 4);
  run = test::run_kinray("regress" + common, folder);
  EXPECT_EQ(run.status, 1) << run.out << run.err;
  EXPECT_NE(run.out.find("FAILED"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::is_regular_file(folder / "report" / "wavy-sphere" / "reference_diff_00000.png"));

  run = test::run_kinray("regress --case no-such-case --references " + refs, folder);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("--case"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("wavy-sphere"), std::string::npos) << "the error lists the cases: " << run.err;
}

}  // namespace
}  // namespace kinray
