#pragma once
// `kinray bench SCENE --aa exact`: the equal-quality antialiasing comparison
// (verification/antialiasing_bench.h) instead of the frame-time sweeps.
#include <CLI/CLI.hpp>
#include <string>

#include "renderer/job/render_job.h"

namespace kinray {

/// Frame rate of the compared frames: consecutive frames of a shot, as motion blur's default.
inline constexpr double kAntialiasingBenchFps = 24;

struct AntialiasingBenchOptions {
  Antialiasing aa = Antialiasing::none;  ///< --aa: exact runs the comparison
  std::string sample_counts = "1,4,16,64,256,1024";
  int frames = 4;
};

/// --aa, --aa-sample-counts, --aa-frames (the reference's samples are --reference-samples, shared
/// with --shutter).
void add_antialiasing_bench_options(CLI::App& command, AntialiasingBenchOptions& options);

/// Runs the comparison on base's scene (size, threads, camera and model flags, --time's start),
/// prints a table, writes {"antialiasing": {...}} to `json` and the chart of error against time
/// per frame into the folder `charts` (antialiasing.png) when given; with base.shutter the
/// frames are blurred (the space-time box filter). Throws InputError naming the flag for bad
/// counts, or lights with --shutter. With lights every method shades them with shadows.
void run_antialiasing_bench_command(const RenderParams& base,
                                    const AntialiasingBenchOptions& options, int reference_samples,
                                    const std::string& json, const std::string& charts, bool quiet);

}  // namespace kinray
