#pragma once
// `kinray bench --shutter S`: the equal-quality motion blur comparison
// (verification/motion_blur_bench.h) over SCENE and --blur-scenes, instead of the frame-time
// sweeps.
#include <CLI/CLI.hpp>
#include <string>

#include "renderer/job/render_job.h"

namespace kinray {

struct MotionBlurBenchOptions {
  double shutter = 0;
  std::string samples = "4,16,64,256";
  int reference_samples = 4096;
  std::string scenes;  ///< more scenes, comma-separated
  double fps = 24;
  int frames = 4;
  int order = 0;  ///< the kinetic frames' Gauss-Legendre nodes per interval (0: the default)
};

/// --shutter, --shutter-order, --blur-samples, --reference-samples, --blur-scenes, --blur-fps,
/// --blur-frames.
void add_motion_blur_bench_options(CLI::App& command, MotionBlurBenchOptions& options);

/// `params` restricted to `frames` frames at multiples of 1/fps, from --time's start (rounded up
/// to a multiple) or centred in the shot; bad values throw InputError naming fps_flag or
/// frames_flag.
[[nodiscard]] RenderParams centred_frames(RenderParams params, double fps, int frames,
                                          const char* fps_flag, const char* frames_flag);

/// Runs the comparison on every scene (base: scene, size, threads, model flags), prints a table,
/// writes {"motion_blur": {scene: ...}} to `json` and the error-against-time chart into `charts`.
void run_motion_blur_bench_command(const RenderParams& base, const MotionBlurBenchOptions& options,
                                   const std::string& json, const std::string& charts, bool quiet);

}  // namespace kinray
