// kinray video DIR --out FILE [--fps F]: assembles the frame_NNNNN.png files of a folder (the
// output of one render, or of the chunks of a render farm) into a video. The frames must be
// consecutive (a missing chunk is reported, not skipped) and of one size.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <regex>
#include <string>
#include <vector>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "renderer/output/video_writer.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

struct VideoOptions {
  std::string folder, out;
  double fps = 24;
};

/// The frame files of `folder` by index, checked to be consecutive.
std::vector<fs::path> frame_files(const std::string& folder) {
  std::error_code error;
  if (!fs::is_directory(folder, error)) throw InputError(folder, "not a folder");
  const std::regex name("frame_([0-9]{5,})\\.png");
  std::vector<std::pair<size_t, fs::path>> frames;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    std::smatch match;
    const std::string file = entry.path().filename().string();
    if (std::regex_match(file, match, name))
      frames.emplace_back(std::stoull(match[1]), entry.path());
  }
  if (frames.empty()) throw InputError(folder, "holds no frame_NNNNN.png files");
  std::sort(frames.begin(), frames.end());
  std::vector<fs::path> paths;
  for (size_t k = 0; k < frames.size(); ++k) {
    const size_t expected = frames.front().first + k;
    if (frames[k].first != expected) {
      char missing[32];
      std::snprintf(missing, sizeof missing, "frame_%05zu.png", expected);
      throw InputError(folder, std::string(missing) + " is missing (frames must be consecutive)");
    }
    paths.push_back(frames[k].second);
  }
  return paths;
}

void run_video(const VideoOptions& options) {
  if (!(options.fps > 0 && options.fps <= 1000)) throw InputError("--fps", "must lie in (0, 1000]");
  VideoWriter::validate_path(options.out);
  check_output_file(options.out, "--out");  // before the encoder, which would only say it failed
  const std::vector<fs::path> frames = frame_files(options.folder);
  const cv::Mat first = read_color_png(frames.front().string());
  if (first.cols < 2 || first.rows < 2)
    throw InputError(frames.front().string(),
                     "is " + std::to_string(first.cols) + "x" + std::to_string(first.rows) +
                         "; video encoders need frames of at least 2x2 pixels");
  create_output_folder(fs::path(options.out).parent_path(), "--out");
  VideoWriter video(options.out, first.cols, first.rows, options.fps);
  for (const fs::path& path : frames) {
    const cv::Mat image = path == frames.front() ? first : read_color_png(path.string());
    if (image.cols != first.cols || image.rows != first.rows)
      throw InputError(path.string(), "is " + std::to_string(image.cols) + "x" +
                                          std::to_string(image.rows) + ", the first frame " +
                                          std::to_string(first.cols) + "x" +
                                          std::to_string(first.rows));
    video.write(image);
  }
  video.close();
  std::printf("video: %s (%s, %zu frames %s .. %s at %g fps)\n", options.out.c_str(),
              video.codec().c_str(), frames.size(), frames.front().filename().c_str(),
              frames.back().filename().c_str(), options.fps);
}

}  // namespace

void register_video_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "video",
      "Assemble the frame_NNNNN.png files of a folder (e.g. render-farm chunks) into a video");
  auto options = std::make_shared<VideoOptions>();
  command->add_option("DIR", options->folder, "Folder of frame_NNNNN.png files")->required();
  command->add_option("--out", options->out, "The video: FILE.mp4 (FFmpeg) or FILE.avi (MJPG)")
      ->required();
  command->add_option("--fps", options->fps, "Frames per second")->capture_default_str();
  command->callback([options] { run_video(*options); });
}

}  // namespace kinray
