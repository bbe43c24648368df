#include "tools/bench_motion_blur.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "tools/cli_options.h"
#include "util/input_error.h"
#include "verification/benchmark.h"
#include "verification/motion_blur_bench.h"

namespace kinray {

void add_motion_blur_bench_options(CLI::App& command, MotionBlurBenchOptions& options) {
  const char* group = "Motion blur (with --shutter)";
  command
      .add_option("--shutter", options.shutter,
                  "Compare motion blur at this shutter (fraction of the frame interval) instead of "
                  "the sweeps")
      ->group(group);
  command
      .add_option("--shutter-order", options.order,
                  "Kinetic: Gauss-Legendre nodes (and light-mask probes) per front interval "
                  "(0: default 4)")
      ->capture_default_str()
      ->group(group);
  command.add_option("--blur-samples", options.samples, "Embree time samples per pixel, a list")
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--reference-samples", options.reference_samples,
                  "Samples per pixel of the Embree reference frame: time samples with --shutter, "
                  "antialiasing samples (a square) with --aa exact")
      ->capture_default_str()
      ->group(group);
  command.add_option("--blur-scenes", options.scenes, "More scenes to compare, comma-separated")
      ->group(group);
  command.add_option("--blur-fps", options.fps, "Frame rate of the compared frames")
      ->capture_default_str()
      ->group(group);
  command
      .add_option(
          "--blur-frames", options.frames,
          "Frames per scene, at the frame rate, centred in the shot (or from --time's start)")
      ->capture_default_str()
      ->group(group);
}

RenderParams centred_frames(RenderParams params, double fps, int frames, const char* fps_flag,
                            const char* frames_flag) {
  if (!(fps > 0) || !std::isfinite(fps)) throw InputError(fps_flag, "must be a finite number > 0");
  if (frames < 2 || frames > 1000)
    throw InputError(frames_flag, "must lie in 2..1000 (the first frame is the warm-up)");
  double start = 0;
  if (params.time) {
    start = params.time->first;
  } else {
    RenderParams probe = params;
    probe.frames = 2;
    const RenderJob job(probe);
    const double middle = (job.frame_times().front() + job.frame_times().back()) / 2;
    start = middle - (frames - 1) / (2 * fps);
  }
  start = std::ceil(start * fps - 1e-9) / fps;
  params.time = std::make_pair(start, start + (frames - 0.5) / fps);
  params.frames.reset();
  params.inbetweens.reset();
  params.fps = fps;
  return params;
}

namespace {

RenderParams scene_params(RenderParams params, const MotionBlurBenchOptions& options) {
  params = centred_frames(params, options.fps, options.frames, "--blur-fps", "--blur-frames");
  params.shutter.shutter = options.shutter;
  params.shutter.order = options.order;
  return params;
}

}  // namespace

void run_motion_blur_bench_command(const RenderParams& base, const MotionBlurBenchOptions& options,
                                   const std::string& json, const std::string& charts, bool quiet) {
  MotionBlurBenchParams bench;
  bench.samples = parse_int_list(options.samples, "--blur-samples");
  bench.reference_samples = options.reference_samples;
  std::vector<std::string> scenes = {base.scene};
  std::stringstream in(options.scenes);
  for (std::string item; std::getline(in, item, ',');)
    if (!item.empty()) scenes.push_back(item);
  // Every scene and flag is checked before anything is measured.
  std::vector<RenderParams> runs;
  for (const std::string& scene : scenes) {
    RenderParams params = base;
    params.scene = scene;
    runs.push_back(scene_params(params, options));
    validate(runs.back());
  }
  std::vector<MotionBlurResult> results;
  nlohmann::json all = nlohmann::json::object();
  for (const RenderParams& params : runs) {
    results.push_back(run_motion_blur_bench(params, bench, [&](const std::string& line) {
      if (!quiet) std::fprintf(stderr, "%s\n", line.c_str());
    }));
    all[params.scene] = results.back().to_json();
  }
  std::printf("motion blur, shutter %g, %dx%d, reference %d samples per pixel\n", options.shutter,
              base.width, base.height, bench.reference_samples);
  std::printf("%-40s %-10s %12s %12s %12s\n", "scene", "method", "ms/frame", "rmse", "max");
  for (const MotionBlurResult& r : results) {
    std::printf("%-40s %-10s %12.2f %12.3g %12.3g\n", r.scene.c_str(), "kinetic",
                r.kinetic.ms_per_frame, r.kinetic.rmse, r.kinetic.max_error);
    for (const MotionBlurPoint& p : r.embree)
      std::printf("%-40s embree/%-3d %12.2f %12.3g %12.3g\n", r.scene.c_str(), p.samples,
                  p.ms_per_frame, p.rmse, p.max_error);
    std::printf("%-40s targets %s\n", r.scene.c_str(), r.meets_targets() ? "met" : "NOT met");
  }
  if (!json.empty())
    write_file_atomically(json, nlohmann::json({{"motion_blur", all}}).dump(2) + "\n");
  if (!charts.empty()) {
    create_output_folder(charts, "--charts");
    const std::string path = (std::filesystem::path(charts) / "motion_blur.png").string();
    write_motion_blur_chart(results, path);
    std::printf("chart: %s\n", path.c_str());
  }
}

}  // namespace kinray
