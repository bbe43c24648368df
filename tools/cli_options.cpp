#include "tools/cli_options.h"

#include <cstdlib>
#include <system_error>
#include <tuple>
#include <vector>

#include "renderer/job/frame_schedule.h"
#include "tools/cli/frame_slice_flags.h"
#include "tools/cli/image_flags.h"
#include "tools/cli/light_flag.h"
#include "tools/slurm_chunk.h"
#include "util/input_error.h"

namespace kinray {

RenderParams RenderOptions::resolve() const {
  RenderParams resolved = params;
  std::tie(resolved.width, resolved.height) = parse_size(size);
  resolved.scene_size = !(size_option && size_option->count() > 0);
  if (frames_option && frames_option->count() > 0) resolved.frames = frames;
  if (fps_option && fps_option->count() > 0) resolved.fps = fps;
  if (inbetweens_option && inbetweens_option->count() > 0) resolved.inbetweens = inbetweens;
  if (time_option && time_option->count() > 0) resolved.time = parse_time_range(time);
  if (aov_option && aov_option->count() > 0) resolved.aov = parse_aov(aov);
  if (!chunk.empty())
    resolved.chunk = chunk == "slurm" ? slurm_array_chunk(std::getenv) : parse_chunk(chunk);
  if (!frame_range.empty()) resolved.frame_range = parse_frame_range(frame_range);
  for (const std::string& light : lights) resolved.lights.push_back(parse_light_flag(light));
  resolved.camera = parse_camera_params(camera);
  validate(resolved);
  return resolved;
}

void add_scene_options(CLI::App& command, RenderOptions& options) {
  command
      .add_option(
          "SCENE", options.params.scene,
          "A built-in scene with parameters (wavy-sphere:triangles=40000), a .json scene file, "
          "a model file, or a mesh sequence (a folder or a quoted glob of .ply/.obj files)")
      ->required();
  command
      .add_option("--animation", options.params.animation,
                  "Model files: the animation to play (name or index)")
      ->group("Scene");
  command
      .add_option(
          "--keyrate", options.params.keyrate,
          "Model files: resample the animation at this many keys per second (0: its own keys); "
          "mesh sequences: one file per key at this rate (0: 24)")
      ->group("Scene");
}

CLI::Validator int_member(std::span<const int> allowed) {
  std::string names;
  for (int value : allowed) names += (names.empty() ? "" : ", ") + std::to_string(value);
  return CLI::Validator(
      [allowed = std::vector<int>(allowed.begin(), allowed.end()),
       names](const std::string& value) {
        for (int a : allowed)
          if (value == std::to_string(a)) return std::string();
        return "must be one of " + names + ", got '" + value + "'";
      },
      "");
}

CLI::Option* add_size_option(CLI::App& command, RenderOptions& options, const std::string& help) {
  options.size_option = command.add_option("--size", options.size, help)->capture_default_str();
  return options.size_option;
}

CLI::Option* add_time_option(CLI::App& command, std::string& time, const std::string& help) {
  return command.add_option("--time", time, help);
}

CLI::Option* add_threads_option(CLI::App& command, int& threads, const std::string& help) {
  return command.add_option("--threads", threads, help)->capture_default_str();
}

CLI::Option* add_sort_option(CLI::App& command, DepthSortKind& sort) {
  return add_enum_option(command, "--sort", sort, kDepthSortNames,
                         "Kinetic: per-pixel depth order");
}

void add_frame_options(CLI::App& command, RenderOptions& options) {
  const char* group = "Frames";
  add_size_option(command, options, "Image size WxH (default: the scene's own, else 512x512)")
      ->group(group);
  options.frames_option =
      command
          .add_option("--frames", options.frames,
                      "N frames evenly over the shot, both ends included (default 24)")
          ->group(group);
  options.fps_option =
      command
          .add_option("--fps", options.fps, "A frame at every multiple of 1/F s inside the shot")
          ->group(group);
  options.inbetweens_option = command
                                  .add_option("--inbetweens", options.inbetweens,
                                              "K frames per keyframe interval, plus the last key")
                                  ->group(group);
  options.frames_option->excludes(options.fps_option)->excludes(options.inbetweens_option);
  options.fps_option->excludes(options.inbetweens_option);
  options.time_option =
      add_time_option(command, options.time, "Restrict the shot to [A, B] seconds, given as A:B")
          ->group(group);
  command
      .add_option("--shutter", options.params.shutter.shutter,
                  "Motion blur: shutter open for this fraction of the frame interval, centred on "
                  "each frame (0.5: 180 degrees; 0: sharp)")
      ->group(group);
  command
      .add_option("--shutter-samples", options.params.shutter.samples,
                  "Motion blur, sampling backends: stratified time samples per pixel")
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--shutter-order", options.params.shutter.order,
                  "Motion blur, kinetic: Gauss-Legendre nodes per front interval, with --aa "
                  "exact per piece of the window (0: default 4)")
      ->capture_default_str()
      ->group(group);
  add_enum_option(command, "--aa", options.params.aa, kAntialiasingNames,
                  "Antialiasing: none (the pixel's centre) or exact (kinetic: the box-filtered "
                  "mean over the pixel's square, from its visible regions; with --shutter over "
                  "the square and the shutter window)")
      ->group(group);
  command
      .add_option("--aa-samples", options.params.aa_samples,
                  "Antialiasing, sampling backends (embree): stratified jittered samples per "
                  "pixel, box-filtered (a square: 1, 4, 16, 64, ...; 1: the pixel's centre); "
                  "with --shutter, samples in (x, y, t)")
      ->capture_default_str()
      ->group(group);
  add_threads_option(command, options.params.threads, "Render threads (0: all cores)")
      ->group(group);
}

CLI::Option* add_light_option(CLI::App& command, std::vector<std::string>& lights) {
  return command
      .add_option("--light", lights,
                  "A world-space light, point:X,Y,Z[:R,G,B] or dir:X,Y,Z[:R,G,B] (repeatable; "
                  "replaces the scene's lights)")
      ->allow_extra_args(false);
}

void add_backend_options(CLI::App& command, RenderOptions& options) {
  const char* group = "Backend";
  command.add_option("--backend", options.params.backend,
                     "auto | kinetic | embree | osmesa (auto: the faster of kinetic and Embree, measured "
                     "on the shot's first frames)")
      ->capture_default_str()
      ->group(group);
  add_enum_option(command, "--embree-mode", options.params.embree_mode, kEmbreeBuildNames,
                  "Embree: rebuild or refit the BVH each frame")
      ->group(group);
  command
      .add_option("--packet", options.params.packet,
                  "Embree: single rays (1) or 4/8/16-wide ray packets")
      ->check(int_member(kEmbreePacketWidths))
      ->capture_default_str()
      ->group(group);
  add_sort_option(command, options.params.sort)->group(group);
  add_light_option(command, options.lights)->group(group);
  add_enum_option(command, "--shadow-tree", options.params.shadow_tree, kShadowTreeNames,
                  "Kinetic: what traces shadow rays")
      ->group(group);
  command
      .add_flag("--audit", options.params.audit,
                "Kinetic: re-check every certificate between events (slow)")
      ->group(group);
}

void add_camera_options(CLI::App& command, CameraParams& camera) {
  const char* group = "Camera";
  command
      .add_option("--camera", camera.camera,
                  "auto: frame the scene automatically; model: the scene's own camera (a model "
                  "file's, an error if it has none). Default: the scene's own, else auto")
      ->group(group);
  command.add_option("--eye", camera.eye, "An explicit still camera at X,Y,Z (with --target)")
      ->group(group);
  command
      .add_option("--target", camera.target, "The point X,Y,Z the --eye camera looks at (up: +y)")
      ->group(group);
  command
      .add_option("--fov", camera.fov,
                  "Vertical field of view in degrees, in (0.5, 179.5), of the camera used "
                  "(default: the camera's own; 45 for --eye and automatic framing)")
      ->group(group);
}

CLI::Option* output_path(CLI::Option* option) {
  return option->check(CLI::Validator(
      [](const std::string& value) {
        return value.empty() ? std::string("the path is empty (an unset shell variable?)")
                             : std::string();
      },
      "PATH"));
}

void add_output_options(CLI::App& command, RenderOptions& options) {
  const char* group = "Output";
  output_path(command.add_option("--out", options.params.out,
                                 "Folder for the frames (default out/<scene-name>)"))
      ->group(group);
  output_path(command.add_option("--video", options.params.video,
                                 "Also encode a video: FILE.mp4 (FFmpeg) or FILE.avi (MJPG)"))
      ->group(group);
  options.aov_option = command
                           .add_option("--aov", options.aov,
                                       "Also write lossless buffers, comma-separated: id "
                                       "(id_NNNNN.png), depth (depth_NNNNN.tiff)")
                           ->group(group);
  output_path(command.add_option("--stats", options.params.stats,
                                 "Write timings and counters as JSON to FILE.json"))
      ->group(group);
  command.add_flag("-q,--quiet", options.params.quiet, "No progress bar and no summary")
      ->group(group);
}

void add_render_options(CLI::App& command, RenderOptions& options) {
  add_scene_options(command, options);
  add_frame_options(command, options);
  add_backend_options(command, options);
  add_camera_options(command, options.camera);
  add_output_options(command, options);
}

}  // namespace kinray
