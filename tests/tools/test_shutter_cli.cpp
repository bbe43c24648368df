// `--shutter` as a user runs it: bad values are one line naming the flag and exit 2 with nothing
// written; a blurred render writes its frames and an id buffer equal to the sharp render's; `diff
// --shutter` passes for the kinetic backend and reports RMSE and max error; `bench --shutter`
// writes the "motion_blur" JSON.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "renderer/output/image_io.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

class ShutterCli : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_shutter_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(::getpid()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  [[nodiscard]] test::CommandRun kinray(const std::string& args) const {
    return test::run_kinray(args, m_dir);
  }
  [[nodiscard]] std::string path(const std::string& name) const { return (m_dir / name).string(); }
  fs::path m_dir;
};

constexpr const char* kScene = "wavy-sphere:triangles=600 --size 40x40 --time 1:1.1 --frames 2";

TEST_F(ShutterCli, BadValuesNameTheFlagAndWriteNothing) {
  for (const char* bad :
       {"--shutter 1.5", "--shutter -1", "--shutter nan", "--shutter 0.5 --shutter-samples 0",
        "--shutter 0.5 --shutter-order 99"}) {
    const auto run = kinray(std::string("render ") + kScene + " " + bad + " --out " + path("out"));
    EXPECT_EQ(run.status, 2) << bad << ": " << run.err;
    EXPECT_EQ(run.err.find("kinray: error: --shutter"), 0u) << bad << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(path("out"))) << bad;
  }
}

TEST_F(ShutterCli, BlurredFramesKeepTheSharpIds) {
  const auto blurred = kinray(std::string("render ") + kScene +
                              " --shutter 0.5 --aov id --audit --quiet --out " + path("b"));
  ASSERT_EQ(blurred.status, 0) << blurred.err;
  const auto sharp =
      kinray(std::string("render ") + kScene + " --aov id --quiet --out " + path("s"));
  ASSERT_EQ(sharp.status, 0) << sharp.err;
  for (const char* name : {"id_00000.png", "id_00001.png"})
    EXPECT_EQ(test::read_text(path("b/") + name), test::read_text(path("s/") + name)) << name;
  EXPECT_NE(test::read_text(path("b/frame_00001.png")), test::read_text(path("s/frame_00001.png")));
}

TEST_F(ShutterCli, DiffComparesWithTheReferenceWithinTheTolerance) {
  const auto run = kinray(std::string("diff ") + kScene +
                          " --shutter 0.5 --reference-samples 256 --json " + path("d.json"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const auto summary = nlohmann::json::parse(test::read_text(path("d.json")));
  EXPECT_EQ(summary["reference_samples"], 256);
  EXPECT_EQ(summary["frames_outside"], 0);
  EXPECT_LT(summary["worst_rmse"].get<double>(), 2e-3);
  // Four samples per pixel are far from the reference.
  const auto coarse =
      kinray(std::string("diff ") + kScene +
             " --backend embree --shutter 0.5 --shutter-samples 1 --reference-samples 256 --json " +
             path("c.json"));
  const auto coarse_summary = nlohmann::json::parse(test::read_text(path("c.json")));
  EXPECT_GT(coarse_summary["worst_rmse"].get<double>(), 4 * summary["worst_rmse"].get<double>());
}

TEST_F(ShutterCli, BenchWritesTheMotionBlurJson) {
  const auto run = kinray(
      "bench wavy-sphere:triangles=600 --size 32x32 --shutter 0.5 --blur-samples 4,16 "
      "--reference-samples 64 --blur-frames 2 --quiet --json " +
      path("b.json"));
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const auto json = nlohmann::json::parse(test::read_text(path("b.json")));
  const auto& scene = json["motion_blur"]["wavy-sphere:triangles=600"];
  EXPECT_GT(scene["kinetic"]["ms_per_frame"].get<double>(), 0);
  EXPECT_GE(scene["kinetic"]["rmse"].get<double>(), 0);
  // The time split of the one timed frame lies inside its wall time.
  const auto& kinetic = scene["kinetic"];
  const double events = kinetic["events_ms"], integrate = kinetic["integrate_ms"],
               readout = kinetic["readout_ms"];
  EXPECT_GT(events, 0);
  EXPECT_GT(integrate, 0);
  EXPECT_GE(readout, 0);
  EXPECT_LE(events + integrate + readout, kinetic["ms_per_frame"].get<double>());
  ASSERT_EQ(scene["embree"].size(), 2u);
  EXPECT_EQ(scene["embree"][1]["samples"], 16);
  EXPECT_EQ(kinetic["order"], 4);  // the default
  EXPECT_EQ(scene["lights"], 0);
  EXPECT_EQ(scene["tie_pixels"], 0);
}

TEST_F(ShutterCli, BenchTakesTheKineticOrderAndRefusesABadOne) {
  const std::string bench =
      "bench wavy-sphere:triangles=600 --size 24x24 --shutter 0.5 --blur-samples 4 "
      "--reference-samples 16 --blur-frames 2 --quiet --json " +
      path("o.json");
  const auto run = kinray(bench + " --shutter-order 2");
  ASSERT_EQ(run.status, 0) << run.out << run.err;
  const auto json = nlohmann::json::parse(test::read_text(path("o.json")));
  EXPECT_EQ(json["motion_blur"]["wavy-sphere:triangles=600"]["kinetic"]["order"], 2);
  const auto bad = kinray(bench + " --shutter-order 99");
  EXPECT_EQ(bad.status, 2) << bad.err;
  EXPECT_EQ(bad.err.find("kinray: error: --shutter-order"), 0u) << bad.err;
  // Without --shutter the sweeps read no blur flag: refused rather than ignored.
  for (const char* flag : {"--shutter-order 8", "--blur-samples 4", "--blur-frames 3"}) {
    const auto ignored = kinray("bench wavy-sphere:triangles=600 --size 24x24 --inbetweens 1 " +
                                std::string(flag) + " --quiet");
    EXPECT_EQ(ignored.status, 2) << flag << ": " << ignored.err;
    EXPECT_NE(ignored.err.find("applies to bench --shutter only"), std::string::npos)
        << ignored.err;
  }
}

}  // namespace
}  // namespace kinray
