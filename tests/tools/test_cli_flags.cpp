// Flags that would be ignored are refused, and a video that cannot have the frames' size says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

class CliFlags : public test::CommandTest {
 protected:
  /// Each command exits 2 with one error line that starts with its expected text.
  void expect_refused(const std::vector<std::pair<std::string, std::string>>& cases) {
    for (const auto& [args, line] : cases) {
      SCOPED_TRACE(args);
      const test::CommandRun run = kinray(args);
      EXPECT_EQ(run.status, 2);
      EXPECT_EQ(run.err.rfind("kinray: error: " + line, 0), 0u) << run.err;
    }
  }
};

TEST_F(CliFlags, FlagsThatNothingReadsAreRefused) {
  const std::string render =
      "render wavy-sphere:triangles=600 --size 16x16 --frames 1 --out '" + path("f") + "' ";
  const std::string diff = "diff wavy-sphere:triangles=600 --size 16x16 --frames 1 ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {render + "--backend kinetic --packet 8", "--packet: applies to the embree backend only"},
      {render + "--backend kinetic --embree-mode rebuild",
       "--embree-mode: applies to the embree backend only"},
      {render + "--backend embree --audit", "--audit: applies to the kinetic backend only"},
      {render + "--backend osmesa --sort heap", "--sort: applies to the kinetic backend only"},
      {render + "--animation walk", "--animation: applies to model files only"},
      {render + "--keyrate 30", "--keyrate: applies to model files only"},
      {"render " + std::string(KINRAY_SOURCE_DIR) + "/scenes/examples/orbit.json --animation 1",
       "--animation: applies to model files only"},
      {diff + "--against osmesa --packet 4", "--packet: applies to the embree backend only"},
  };
  expect_refused(cases);
  EXPECT_FALSE(fs::exists(path("f")));
  // Where a flag is read it is accepted: diff's reference is Embree, which takes --packet, and
  // render's --backend auto chooses Embree for a flag of Embree's.
  const test::CommandRun run = kinray(diff + "--packet 4 --quiet");
  EXPECT_EQ(run.status, 0) << run.err;
  const test::CommandRun chosen = kinray(render + "--packet 4 --quiet --stats '" + path("s.json") + "'");
  EXPECT_EQ(chosen.status, 0) << chosen.err;
  EXPECT_NE(test::read_text(path("s.json")).find("\"backend\": \"embree\""), std::string::npos);
}

TEST_F(CliFlags, ALibraryFieldIsNamedByItsFlag) {
  // validate() names RenderParams' fields (OptionError); main says the flag the user gave.
  const std::string render = "render wavy-sphere:triangles=600 --out '" + path("f") + "' ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {render + "--frames 0", "--frames: must be at least 1, got 0"},
      {render + "--fps -1", "--fps: must be a finite number > 0, got -1"},
      {render + "--inbetweens 0", "--inbetweens: must be at least 1, got 0"},
      {render + "--threads 5000", "--threads: must lie in 0..4096 (0: all cores), got 5000"},
      {render + "--time 0:99", "--time: [0, 99] is not inside the shot"},
  };
  expect_refused(cases);
  EXPECT_FALSE(fs::exists(path("f")));
}

TEST_F(CliFlags, AVideoOfOddSizeSaysWhatSizeItHas) {
  for (const char* name : {"odd.mp4", "odd.avi"}) {
    SCOPED_TRACE(name);
    const test::CommandRun run =
        kinray("render wavy-sphere:triangles=600 --backend embree --size 33x25 --frames 2 --out '" +
               path("f") + "' --quiet --video '" + path(name) + "'");
    ASSERT_EQ(run.status, 0) << run.err;
    cv::VideoCapture capture(path(name));
    ASSERT_TRUE(capture.isOpened());
    const int width = int(capture.get(cv::CAP_PROP_FRAME_WIDTH));
    const int height = int(capture.get(cv::CAP_PROP_FRAME_HEIGHT));
    if (width == 33 && height == 25) {
      EXPECT_EQ(run.err, "") << "the video has the frames' size: nothing to say";
    } else {
      EXPECT_NE(run.err.find("the video is " + std::to_string(width) + "x" +
                             std::to_string(height) + " (the frames are 33x25)"),
                std::string::npos)
          << run.err;
    }
  }
}

}  // namespace
}  // namespace kinray
