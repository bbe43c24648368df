// kinray video DIR --out FILE: the frames of two render-farm chunks become one video; a missing
// frame is one error line naming the folder and the frame, and no video is written.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;
using test::CommandRun;
using test::run_kinray;

TEST(VideoCommand, AssemblesChunksAndReportsAMissingFrame) {
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_video_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string render = "render orbit:triangles=500 --size 32x24 --frames 6 -q --out '" +
                             (folder / "frames").string() + "' --chunk ";
  ASSERT_EQ(run_kinray(render + "1/2", folder).status, 0);
  const fs::path video = folder / "all.avi";
  const std::string assemble =
      "video '" + (folder / "frames").string() + "' --fps 12 --out '" + video.string() + "'";
  const CommandRun early = run_kinray(assemble, folder);
  EXPECT_EQ(early.status, 0);  // frames 0..2 are consecutive
  ASSERT_EQ(run_kinray(render + "2/2", folder).status, 0);
  const CommandRun whole = run_kinray(assemble, folder);
  EXPECT_EQ(whole.status, 0) << whole.err;
  EXPECT_NE(whole.out.find("6 frames frame_00000.png .. frame_00005.png at 12 fps"),
            std::string::npos)
      << whole.out;
  EXPECT_GT(fs::file_size(video), 0u);

  fs::remove(folder / "frames" / "frame_00004.png");
  fs::remove(video);
  const CommandRun missing = run_kinray(assemble, folder);
  EXPECT_EQ(missing.status, 2);
  EXPECT_EQ(missing.err, "kinray: error: " + (folder / "frames").string() +
                             ": frame_00004.png is missing (frames must be consecutive)\n");
  EXPECT_FALSE(fs::exists(video));
}

}  // namespace
}  // namespace kinray
