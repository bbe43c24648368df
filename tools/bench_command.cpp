// kinray bench SCENE ...: the kinetic backend against every Embree mode on the same frames, in one
// process, with the ID buffers checked while measuring. Sweeps vary one axis at a time around the
// base configuration and are written as JSON, CSV and PNG charts.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "renderer/benchmark.h"
#include "renderer/image_io.h"
#include "scenes/error.h"
#include "tools/bench_motion_blur.h"
#include "tools/cli_options.h"
#include "tools/commands.h"

namespace kinray {
namespace {

struct BenchOptions {
  RenderOptions render;
  std::string inbetweens = "1,4,16", triangles, sizes, thread_counts, embree_modes;
  std::string json, csv, charts;
  int repetitions = 3, reference_frames = 12;
  bool quiet = false;
  MotionBlurBenchOptions motion_blur;  ///< --shutter and its flags
};

BenchParams resolve(const BenchOptions& options) {
  BenchParams params;
  params.base = options.render.resolve();
  params.inbetweens = parse_int_list(options.inbetweens, "--inbetweens");
  if (!options.triangles.empty()) params.triangles = parse_int_list(options.triangles, "--triangles");
  if (!options.sizes.empty()) {
    std::stringstream in(options.sizes);
    for (std::string item; std::getline(in, item, ',');) params.sizes.push_back(parse_size(item, "--sizes"));
  }
  if (!options.thread_counts.empty()) params.threads = parse_int_list(options.thread_counts, "--thread-counts");
  if (!options.embree_modes.empty()) params.embree_modes = parse_embree_modes(options.embree_modes);
  params.repetitions = options.repetitions;
  params.reference_frames = options.reference_frames;
  validate(params);
  return params;
}

void run_bench(const BenchOptions& options) {
  if (options.motion_blur.shutter != 0) {
    RenderParams base = options.render.resolve();
    return run_motion_blur_bench_command(base, options.motion_blur, options.json, options.charts,
                                         options.quiet);
  }
  const BenchParams params = resolve(options);
  // Flags and scene are checked before anything is measured or written.
  for (const std::string* path : {&options.json, &options.csv})
    if (!path->empty() && std::filesystem::is_directory(*path)) throw InputError(*path, "is a folder");
  const BenchReport report = run_benchmark(params, [&](const std::string& line) {
    if (!options.quiet) std::fprintf(stderr, "%s\n", line.c_str());
  });
  report.print(std::cout);
  if (!options.json.empty()) write_file_atomically(options.json, report.to_json().dump(2) + "\n");
  if (!options.csv.empty()) write_file_atomically(options.csv, report.to_csv());
  if (!options.charts.empty())
    for (const std::string& path : report.write_charts(options.charts)) std::printf("chart: %s\n", path.c_str());
  size_t real = 0;
  for (const BenchPoint& point : report.points) real += point.mismatch_real;
  if (real > 0)
    throw std::runtime_error("the kinetic frames disagree with Embree on " + std::to_string(real) +
                             " pixels beyond ties: the figures above are not valid");
}

}  // namespace

void register_bench_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "bench", "Time per frame of the kinetic backend against every Embree mode, side by side, with sweeps");
  auto options = std::make_shared<BenchOptions>();
  add_scene_options(*command, options->render);
  command->add_option("--size", options->render.size, "Base image size WxH")->capture_default_str();
  options->render.time_option =
      command->add_option("--time", options->render.time, "Restrict the shot to [A, B] (seconds), as A:B");
  command->add_option("--threads", options->render.params.threads, "Base thread count (0: all cores)")
      ->capture_default_str();
  command->add_option("--sort", options->render.params.sort, "Kinetic: list | tournament | heap")->capture_default_str();
  command->add_option("--inbetweens", options->inbetweens, "In-betweens per keyframe interval, a list: 1,2,4,...")
      ->capture_default_str();
  command->add_option("--triangles", options->triangles,
                      "Sweep: triangle counts of a built-in scene, a list (at 16 in-betweens)");
  command->add_option("--sizes", options->sizes, "Sweep: image sizes, a list 256x256,512x512,...");
  command->add_option("--thread-counts", options->thread_counts, "Sweep: thread counts, a list 1,2");
  command->add_option("--embree-modes", options->embree_modes,
                      "Embree peers as BUILD/PACKET, a list (default rebuild/1,rebuild/8,refit/1,refit/4,refit/8,refit/16)");
  command->add_option("--repetitions", options->repetitions, "Medians over this many runs")->capture_default_str();
  command->add_option("--reference-frames", options->reference_frames,
                      "Frames per Embree mode, spread over the shot")->capture_default_str();
  command->add_option("--json", options->json, "Write the results as JSON");
  command->add_option("--csv", options->csv, "Write one row per configuration and backend mode as CSV");
  command->add_option("--charts", options->charts, "Write PNG charts of each sweep into this folder");
  command->add_flag("-q,--quiet", options->quiet, "No progress lines");
  add_motion_blur_bench_options(*command, options->motion_blur);
  command->callback([options] { run_bench(*options); });
}

}  // namespace kinray
