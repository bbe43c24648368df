// kinray render SCENE ...: renders a scene to a PNG sequence (and optionally a video, ID and depth
// buffers, and a --stats JSON). Every flag is checked and the scene loaded before the first file
// is touched, so bad input never harms earlier output.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <system_error>
#include <utility>

#include "renderer/image_io.h"
#include "renderer/video_writer.h"
#include "scenes/error.h"
#include "scenes/scene_loader.h"
#include "tools/cli_options.h"
#include "tools/commands.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

std::string numbered(const std::string& prefix, size_t index, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu%s", prefix.c_str(), index, extension);
  return name;
}

/// Frames per second for the video: --fps when given, else the mean spacing of the frame times.
double video_fps(const RenderParams& params, const std::vector<double>& times) {
  if (params.fps) return *params.fps;
  if (times.size() < 2 || !(times.back() > times.front())) return 24;
  return std::clamp(double(times.size() - 1) / (times.back() - times.front()), 1.0, 240.0);
}

void check_output_paths(const std::string& out, const RenderParams& params) {
  std::error_code error;
  if (fs::exists(out, error) && !fs::is_directory(out, error))
    throw InputError("--out", "'" + out + "' exists and is not a folder");
  if (!params.stats.empty() && fs::is_directory(params.stats, error))
    throw InputError("--stats", "'" + params.stats + "' is a folder");
  // A file where a folder must be would only fail after the whole render.
  for (const auto& [file, flag] :
       {std::pair{params.stats, "--stats"}, std::pair{params.video, "--video"}}) {
    for (fs::path parent = fs::path(file).parent_path(); !parent.empty();
         parent = parent.parent_path()) {
      if (fs::exists(parent, error)) {
        if (!fs::is_directory(parent, error))
          throw InputError(flag, "'" + parent.string() + "' is not a folder");
        break;
      }
      if (parent == parent.parent_path()) break;
    }
  }
}

void run_render(const RenderParams& flags) {
  RenderJob job(flags);
  const RenderParams& params = job.params();  // with the scene's own size and frame count
  std::unique_ptr<Backend> backend = job.make_backend();
  const std::string out = output_folder(params);
  check_output_paths(out, params);

  // Everything is valid: from here on files are written.
  create_folder(out, "--out");
  std::unique_ptr<VideoWriter> video;
  if (!params.video.empty()) {
    create_folder(fs::path(params.video).parent_path(), "--video");
    video = std::make_unique<VideoWriter>(params.video, params.width, params.height,
                                          video_fps(params, job.frame_times()));
  }
  const bool write_id = std::find(params.aov.begin(), params.aov.end(), "id") != params.aov.end();
  const bool write_depth =
      std::find(params.aov.begin(), params.aov.end(), "depth") != params.aov.end();
  const fs::path folder(out);
  const RenderTimings& timings = job.run(*backend, [&](size_t index, const Frame& frame) {
    write_color_png((folder / numbered("frame", index, ".png")).string(), frame);
    if (write_id) write_id_png((folder / numbered("id", index, ".png")).string(), frame);
    if (write_depth) write_depth_tiff((folder / numbered("depth", index, ".tiff")).string(), frame);
    if (video) video->write(frame);
  });
  if (video) video->close();
  if (!params.stats.empty()) {
    create_folder(fs::path(params.stats).parent_path(), "--stats");
    nlohmann::json stats = render_stats(job, *backend);
    if (video)
      stats["video"] = {
          {"path", params.video}, {"codec", video->codec()}, {"frames", video->frames_written()}};
    write_file_atomically(params.stats, stats.dump(2) + "\n");
  }
  if (!params.quiet) {
    const size_t n = timings.frames;
    std::printf("rendered %zu frame%s of %s (%zu triangles, %dx%d) with %s in %.2f s\n", n,
                n == 1 ? "" : "s", params.scene.c_str(), job.scene().triangle_count(), params.width,
                params.height, backend->name().c_str(), timings.total);
    const FrameSlice& slice = job.slice();
    const std::string last = n > 1 ? " .. " + numbered("frame", slice.end - 1, ".png") : "";
    std::printf("frames: %s/%s%s\n", out.c_str(), numbered("frame", slice.begin, ".png").c_str(),
                last.c_str());
    if (video) std::printf("video:  %s (%s)\n", params.video.c_str(), video->codec().c_str());
    if (!params.stats.empty()) std::printf("stats:  %s\n", params.stats.c_str());
  }
}

}  // namespace

void register_render_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand("render",
                                         "Render a scene to PNG frames out/<scene>/frame_00000.png "
                                         "... (and a video, ID/depth buffers, stats)");
  auto options = std::make_shared<RenderOptions>();
  add_render_options(*command, *options);
  command
      ->add_option("--chunk", options->params.chunk,
                   "Render farms: only the I-th of N consecutive slices of the frames (I/N, 1-based)")
      ->group("Frames");
  command
      ->add_option("--frame-range", options->params.frame_range,
                   "Render farms: only frames A..B of the schedule (A:B, 0-based, both included)")
      ->group("Frames");
  command->footer(describe_scene_spec_syntax());
  command->callback([options] { run_render(options->resolve()); });
}

}  // namespace kinray
