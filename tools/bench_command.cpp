// kinray bench SCENE ...: the kinetic backend against every Embree mode on the same frames, in one
// process, with the ID buffers checked while measuring. Sweeps vary one axis at a time around the
// base configuration and are written as JSON, CSV and PNG charts.
#include <array>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <tuple>
#include <vector>

#include "renderer/job/memory_estimate.h"
#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "scenes/scene_loader.h"
#include "tools/bench_antialiasing.h"
#include "tools/bench_motion_blur.h"
#include "tools/bench_suite_command.h"
#include "tools/cli/image_flags.h"
#include "tools/cli_errors.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/option_scope.h"
#include "tools/tree_bench_command.h"
#include "util/input_error.h"
#include "verification/benchmark.h"
#include "verification/collide_bench.h"

namespace kinray {
namespace {

struct BenchOptions {
  RenderOptions render;
  std::string inbetweens = "1,4,16", triangles, sizes, thread_counts, embree_modes;
  std::string json, csv, charts;
  std::string structure = "grid";  ///< grid, or kinetic trees (tools/tree_bench_command.cpp)
  int repetitions = 3, reference_frames = 12;
  bool quiet = false;
  MotionBlurBenchOptions motion_blur;  ///< --shutter and its flags
  AntialiasingBenchOptions antialiasing;  ///< --aa exact and its flags
  SuiteOptions suite;                  ///< --suite and its flags
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

/// --repetitions and --reference-frames within their bounds (bench and bench --suite).
void check_limits(const BenchParams& params) {
  if (params.repetitions > 1000)
    throw InputError("--repetitions",
                     "must lie in 1..1000, got " + std::to_string(params.repetitions));
  if (params.reference_frames > 10000)
    throw InputError("--reference-frames",
                     "must lie in 1..10000, got " + std::to_string(params.reference_frames));
}

/// Every configuration the sweeps will run, checked before the first one runs: flags, the frame
/// schedule on the scene's key grid, memory, and --triangles only on a built-in scene.
void check_configurations(const BenchParams& params) {
  const RenderParams& base = params.base;
  check_limits(params);
  const bool builtin = builtin_scene_params(base.scene).has_value();
  if (!params.triangles.empty() && !builtin)
    throw InputError("--triangles", "sweeps the triangles= parameter of a built-in scene, and '" +
                                        base.scene + "' is not one");
  std::vector<std::pair<const char*, RenderParams>> configurations;  // the sweep's flag, params
  for (int k : params.inbetweens) {
    RenderParams p = base;
    p.inbetweens = k;
    configurations.emplace_back("--inbetweens", p);
  }
  for (int n : params.triangles) {
    RenderParams p = base;
    p.scene = with_triangles(base.scene, n);
    configurations.emplace_back("--triangles", p);
  }
  for (const auto& [w, h] : params.sizes) {
    RenderParams p = base;
    std::tie(p.width, p.height) = std::pair{w, h};
    configurations.emplace_back("--sizes", p);
  }
  for (int n : params.threads) {
    RenderParams p = base;
    p.threads = n;
    configurations.emplace_back("--thread-counts", p);
  }
  // The key grid the in-betweens subdivide: a built-in's from its parameters, else the scene's.
  const std::vector<double> keys =
      builtin ? [&] {
        const ProceduralParams scene = *builtin_scene_params(base.scene);
        return procedural_key_times(scene.duration, scene.keyrate);
      }()
              : load_scene(base.scene, model_options(base)).key_times();
  for (const auto& [flag, p] : configurations) {
    try {
      (void)builtin_scene_params(p.scene);
      validate(p);
      check_render_memory(p, nullptr);
      RenderParams kinetic = p;
      kinetic.backend = "kinetic";
      check_render_memory(kinetic, nullptr);
      (void)frame_times(keys, schedule_params(p));
    } catch (const InputError& error) {
      // A field the library names (OptionError) is reported as its flag, as main would.
      const auto* option = dynamic_cast<const OptionError*>(&error);
      const InputError e = option ? name_the_flag(*option) : error;
      if (e.where() == flag) throw e;
      throw InputError(flag, std::string("in this sweep, ") + e.what());
    }
  }
}

/// `bench --suite`: bench's own flags resolved as for SCENE (the first suite scene), with the
/// suite's size and in-betweens unless given.
/// The sweeps across in-betweens read none of the motion blur comparison's flags: set without
/// --shutter, they would be ignored without a word.
void refuse_blur_flags(const MotionBlurBenchOptions& blur) {
  const MotionBlurBenchOptions unset;
  const auto refuse = [](const char* flag) {
    throw InputError(flag, "applies to bench --shutter only");
  };
  if (blur.order != unset.order) refuse("--shutter-order");
  if (blur.samples != unset.samples) refuse("--blur-samples");
  if (!blur.scenes.empty()) refuse("--blur-scenes");
  if (blur.fps != unset.fps) refuse("--blur-fps");
  if (blur.frames != unset.frames) refuse("--blur-frames");
}

void run_suite_bench(const BenchOptions& options, const CLI::App& command) {
  std::vector<SuiteScene> scenes = resolve_suite_scenes(options.suite);
  BenchOptions suite = options;
  suite.render.params.scene = scenes.front().spec;
  if (command.get_option("--size")->count() == 0) suite.render.size = kSuiteSize;
  if (command.get_option("--inbetweens")->count() == 0) suite.inbetweens = kSuiteInbetweens;
  const BenchParams params = resolve(suite);
  check_limits(params);
  run_suite_command(options.suite, std::move(scenes), params, options.json, options.quiet);
}

void run_bench(const BenchOptions& options, const CLI::App& command) {
  check_suite_flags(command, options.suite);
  if (options.antialiasing.aa == Antialiasing::exact &&
      (options.suite.enabled || options.structure != "grid"))
    throw InputError("--aa", "bench --aa exact compares one scene's frames; drop " +
                                 std::string(options.suite.enabled ? "--suite" : "--structure"));
  if (options.suite.enabled) return run_suite_bench(options, command);
  const bool collide = options.structure.find("ksl") != std::string::npos ||
                       options.structure.find("swept") != std::string::npos;
  if (collide) {
    run_collide_bench(options.render.params.scene, options.structure, options.inbetweens,
                      options.triangles, options.repetitions, options.json, options.charts,
                      options.quiet);
    return;
  }
  if (options.structure != "grid") {
    run_tree_bench(options.render.resolve(), options.structure, options.inbetweens, options.triangles,
                   options.repetitions, options.json, options.charts, options.quiet);
    return;
  }
  if (options.antialiasing.aa == Antialiasing::exact) {
    if (!options.motion_blur.scenes.empty())
      throw InputError("--blur-scenes", "bench --aa exact compares one scene's frames");
    if (!options.csv.empty())
      throw InputError("--csv", "bench --aa exact writes a table, --json and --charts only");
    // With --shutter every frame is its window's: the space-time box filter.
    RenderParams base = options.render.resolve();
    base.shutter.shutter = options.motion_blur.shutter;
    base.shutter.order = options.motion_blur.order;
    return run_antialiasing_bench_command(base, options.antialiasing,
                                          options.motion_blur.reference_samples, options.json,
                                          options.charts, options.quiet);
  }
  if (options.motion_blur.shutter != 0) {
    RenderParams base = options.render.resolve();
    return run_motion_blur_bench_command(base, options.motion_blur, options.json, options.charts,
                                         options.quiet);
  }
  refuse_blur_flags(options.motion_blur);
  const BenchParams params = resolve(options);
  check_options_apply(params.base, std::array<std::string, 2>{"kinetic", "embree"});
  check_configurations(params);
  // Flags and scene are checked before anything is measured or written.
  if (!options.json.empty()) check_output_file(options.json, "--json");
  if (!options.csv.empty()) check_output_file(options.csv, "--csv");
  if (!options.charts.empty()) check_output_folder(options.charts, "--charts");
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
  add_camera_options(*command, options->render.camera);
  command->get_option("SCENE")->required(false);  // not with --suite; without it, validate() asks
  add_size_option(*command, options->render,
                  "Base image size WxH (default: the scene's own, else 512x512)");
  options->render.time_option = add_time_option(*command, options->render.time,
                                                "Restrict the shot to [A, B] (seconds), as A:B");
  add_threads_option(*command, options->render.params.threads, "Base thread count (0: all cores)");
  add_sort_option(*command, options->render.params.sort);
  add_light_option(*command, options->render.lights);
  command->add_option("--inbetweens", options->inbetweens, "In-betweens per keyframe interval, a list: 1,2,4,...")
      ->capture_default_str();
  command->add_option("--triangles", options->triangles,
                      "Sweep: triangle counts of a built-in scene, a list (at 16 in-betweens)");
  command->add_option("--sizes", options->sizes, "Sweep: image sizes, a list 256x256,512x512,...");
  command->add_option("--thread-counts", options->thread_counts, "Sweep: thread counts, a list 1,2");
  command->add_option("--embree-modes", options->embree_modes,
                      "Embree peers as BUILD/PACKET, a list (default rebuild/1,rebuild/8,refit/1,refit/4,refit/8,refit/16, less the packet widths this machine lacks)");
  command->add_option("--repetitions", options->repetitions, "Medians over this many runs")->capture_default_str();
  command->add_option("--reference-frames", options->reference_frames,
                      "Frames per Embree mode, spread over the shot")->capture_default_str();
  output_path(command->add_option("--json", options->json, "Write the results as JSON"));
  output_path(command->add_option("--csv", options->csv,
                                  "Write one row per configuration and backend mode as CSV"));
  output_path(command->add_option("--charts", options->charts,
                                  "Write PNG charts of each sweep into this folder"));
  command->add_option("--structure", options->structure,
                      "grid (the kinetic grid against Embree), kinetic trees for shadow rays: aabb,boxtree[,refit], "
                      "or collision detection: ksl,swept[,brute] (--inbetweens: collision checks per keyframe interval)")
      ->capture_default_str();
  command->add_flag("-q,--quiet", options->quiet, "No progress lines");
  add_motion_blur_bench_options(*command, options->motion_blur);
  add_antialiasing_bench_options(*command, options->antialiasing);
  add_suite_options(*command, options->suite);
  command->callback([options, command] { run_bench(*options, *command); });
}

}  // namespace kinray
