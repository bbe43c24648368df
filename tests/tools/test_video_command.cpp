// kinray video DIR --out FILE: the frames of two render-farm chunks become one video that plays
// every frame at their size; a missing frame is one error line naming the folder and the frame,
// and no video is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <iterator>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

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
  // decoded as a player would: the six frames, each of the frames' size
  {
    cv::VideoCapture capture(video.string());
    ASSERT_TRUE(capture.isOpened());
    int frames = 0;
    cv::Mat image;
    while (capture.read(image)) {
      ++frames;
      EXPECT_EQ(image.cols, 32);
      EXPECT_EQ(image.rows, 24);
    }
    EXPECT_EQ(frames, 6);
  }

  fs::remove(folder / "frames" / "frame_00004.png");
  fs::remove(video);
  const CommandRun missing = run_kinray(assemble, folder);
  EXPECT_EQ(missing.status, 2);
  EXPECT_EQ(missing.err, "kinray: error: " + (folder / "frames").string() +
                             ": frame_00004.png is missing (frames must be consecutive)\n");
  EXPECT_FALSE(fs::exists(video));
}

// A farm task given --frame-range writes those frames alone, numbered as in the whole render
// and identical to its files byte for byte.
TEST(VideoCommand, AFrameRangeWritesThoseFramesAsTheWholeRenderDoes) {
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_frame_range_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string render = "render orbit:triangles=500 --size 32x24 --frames 6 -q --out '";
  ASSERT_EQ(run_kinray(render + (folder / "whole").string() + "'", folder).status, 0);
  const CommandRun range =
      run_kinray(render + (folder / "range").string() + "' --frame-range 2:3", folder);
  ASSERT_EQ(range.status, 0) << range.err;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder / "range"))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"frame_00002.png", "frame_00003.png"}));
  for (const std::string& name : names)
    EXPECT_EQ(test::read_text(folder / "range" / name), test::read_text(folder / "whole" / name))
        << name;
  fs::remove_all(folder);
}

// A chunk cut short leaves some frames; given again with --skip-existing it renders the missing
// ones only, and the folder is then the whole render's, byte for byte.
TEST(VideoCommand, AResubmittedChunkRendersOnlyTheMissingFrames) {
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_skip_existing_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string render =
      "render orbit:triangles=500 --size 32x24 --frames 6 --aov id -q --out '";
  ASSERT_EQ(run_kinray(render + (folder / "whole").string() + "'", folder).status, 0);
  const fs::path resumed = folder / "resumed";
  fs::create_directories(resumed);
  // what an interrupted chunk left: frames 0, 1 and 4 whole, frame 2 without its id buffer
  for (const char* name : {"frame_00000.png", "id_00000.png", "frame_00001.png", "id_00001.png",
                           "frame_00002.png", "frame_00004.png", "id_00004.png"})
    fs::copy_file(folder / "whole" / name, resumed / name);
  const fs::path stats = folder / "stats.json";
  const CommandRun run = run_kinray(
      render + resumed.string() + "' --skip-existing --stats '" + stats.string() + "'", folder);
  ASSERT_EQ(run.status, 0) << run.err;
  const std::string summary = test::read_text(stats);
  EXPECT_NE(summary.find("\"skipped\": 3"), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"frames\": 3"), std::string::npos) << summary;
  for (const auto& entry : fs::directory_iterator(folder / "whole")) {
    const std::string name = entry.path().filename().string();
    EXPECT_EQ(test::read_text(resumed / name), test::read_text(entry.path())) << name;
  }
  // nothing left to do: nothing rendered, nothing removed
  const CommandRun again = run_kinray(render + resumed.string() + "' --skip-existing", folder);
  EXPECT_EQ(again.status, 0) << again.err;
  EXPECT_EQ(std::distance(fs::directory_iterator(resumed), fs::directory_iterator()), 12);
  // a video needs every frame: refused with the skip
  const CommandRun video = run_kinray(
      render + resumed.string() + "' --skip-existing --video '" + (folder / "v.avi").string() + "'",
      folder);
  EXPECT_EQ(video.status, 2);
  EXPECT_NE(video.err.find("--skip-existing: does not combine with --video"), std::string::npos)
      << video.err;
  fs::remove_all(folder);
}

// `--chunk slurm` takes its slice from the job array's variables, as a batch script passes them.
TEST(VideoCommand, ASlurmArrayTaskRendersItsOwnChunk) {
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_slurm_chunk_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  const std::string render = "render orbit:triangles=500 --size 32x24 --frames 6 -q --out '" +
                             (folder / "frames").string() + "' --chunk slurm";
  // the third of three tasks of --array=4-8:2 (indices 4, 6, 8): frames 4 and 5 of 6
  const CommandRun task =
      run_kinray(render, folder,
                 "env SLURM_ARRAY_TASK_ID=8 SLURM_ARRAY_TASK_MIN=4 SLURM_ARRAY_TASK_STEP=2 "
                 "SLURM_ARRAY_TASK_COUNT=3");
  ASSERT_EQ(task.status, 0) << task.err;
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder / "frames"))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"frame_00004.png", "frame_00005.png"}));
  const CommandRun outside = run_kinray(render, folder, "env -u SLURM_ARRAY_TASK_ID");
  EXPECT_EQ(outside.status, 2);
  EXPECT_NE(outside.err.find("--chunk: slurm: not a task of a Slurm job array"), std::string::npos)
      << outside.err;
  const CommandRun irregular = run_kinray(
      render, folder, "env SLURM_ARRAY_TASK_ID=9 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_COUNT=3");
  EXPECT_EQ(irregular.status, 2);
  EXPECT_NE(irregular.err.find("evenly spaced"), std::string::npos) << irregular.err;
  fs::remove_all(folder);
}

}  // namespace
}  // namespace kinray
