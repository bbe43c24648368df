// --light and --shadow-tree: values parsed as documented, bad ones one clear line naming the flag,
// and `kinray diff` reporting shadow mismatches per light.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "renderer/job/render_job.h"
#include "tests/tools/kinray_process.h"
#include "tools/cli/light_flag.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

TEST(LightFlag, PointAndDirectionalWithAndWithoutColour) {
  const Light point = parse_light_flag("point:1,-2.5,3e1");
  EXPECT_EQ(point.kind, Light::Kind::point);
  EXPECT_EQ(point.position, Vec3(1, -2.5, 30));
  EXPECT_EQ(point.color, Color(1, 1, 1));
  const Light sun = parse_light_flag("dir:0,-3,0:1,0.5,0");
  EXPECT_EQ(sun.kind, Light::Kind::directional);
  EXPECT_EQ(sun.direction, Vec3(0, -1, 0));
  EXPECT_EQ(sun.color, Color(1, 0.5f, 0));
}

TEST(LightFlag, BadValuesNameTheFlag) {
  for (const char* bad :
       {"", "point", "spot:0,0,0", "point:1,2", "point:1,2,3,4", "point:1,,3", "point:a,b,c",
        "point:1,2,nan", "point:1,2,inf", "dir:0,0,0", "point:1,2,3:1,1", "point:1,2,3:1,-1,1",
        "point:1,2,3:", "point: 1,2,3", "point:1,2,3:1,1,1:2"}) {
    try {
      (void)parse_light_flag(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& error) {
      EXPECT_EQ(error.where(), "--light") << bad;
    }
  }
}

TEST(LightFlag, TooManyLightsAndUnknownTreesAreRejected) {
  RenderParams params;
  params.scene = "wavy-sphere";
  params.lights.assign(33, parse_light_flag("point:0,0,0"));
  try {
    validate(params);
    ADD_FAILURE() << "33 lights accepted";
  } catch (const OptionError& error) {
    EXPECT_EQ(error.where(), "lights");  // the field; the command line names --light
  }
}

class LightCli : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_light_cli_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  fs::path m_dir;
};

TEST_F(LightCli, BadLightIsOneLineAndExitTwo) {
  for (const char* bad : {"--light point:1,2", "--light dir:0,0,0", "--light lamp:1,2,3"}) {
    const test::CommandRun run =
        test::run_kinray(std::string("render static-moving --size 8x8 --frames 1 -q ") + bad +
                             " --out '" + (m_dir / "out").string() + "'",
                         m_dir);
    EXPECT_EQ(run.status, 2) << bad;
    EXPECT_EQ(run.err.rfind("kinray: error: --light: ", 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_FALSE(fs::exists(m_dir / "out"));
  }
}

TEST_F(LightCli, DiffReportsShadowMismatchesPerLight) {
  const fs::path json = m_dir / "diff.json";
  const test::CommandRun run = test::run_kinray(
      "diff static-moving --backend kinetic --shadow-tree brute --against embree --size 24x24 "
      "--frames 2 -q --light point:2,5,-3 --light dir:1,-1,0 --json '" +
          json.string() + "'",
      m_dir);
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json summary = nlohmann::json::parse(test::read_text(json));
  ASSERT_EQ(summary["shadows"].size(), 2u);
  for (const nlohmann::json& light : summary["shadows"]) EXPECT_EQ(light["mismatch_real"], 0);
  EXPECT_EQ(summary["mismatch_real"], 0);
  EXPECT_EQ(summary["per_frame"][0]["shadows"].size(), 2u);
}

}  // namespace
}  // namespace kinray
