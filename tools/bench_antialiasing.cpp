#include "tools/bench_antialiasing.h"

#include <cstdio>
#include <filesystem>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "tools/bench_motion_blur.h"
#include "tools/cli_options.h"
#include "util/input_error.h"
#include "verification/antialiasing_bench.h"
#include "verification/benchmark.h"
#include "verification/quality_point.h"

namespace kinray {

void add_antialiasing_bench_options(CLI::App& command, AntialiasingBenchOptions& options) {
  const char* group = "Antialiasing (with --aa exact)";
  add_enum_option(command, "--aa", options.aa, kAntialiasingNames,
                  "exact: compare the kinetic exact antialiasing (with --shutter: the "
                  "space-time box filter) with Embree's supersampling "
                  "instead of the sweeps")
      ->group(group);
  command
      .add_option("--aa-sample-counts", options.sample_counts,
                  "Embree antialiasing samples per pixel, a list of squares")
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--aa-frames", options.frames,
                  "Frames, at 24 fps, centred in the shot (or from --time's start)")
      ->capture_default_str()
      ->group(group);
}

void run_antialiasing_bench_command(const RenderParams& base,
                                    const AntialiasingBenchOptions& options, int reference_samples,
                                    const std::string& json, const std::string& charts,
                                    bool quiet) {
  AntialiasingBenchParams bench;
  bench.samples = parse_int_list(options.sample_counts, "--aa-sample-counts");
  bench.reference_samples = reference_samples;
  RenderParams params =
      centred_frames(base, kAntialiasingBenchFps, options.frames, "--aa-frames", "--aa-frames");
  params.aa = options.aa;
  validate(params);
  if (!json.empty()) check_output_file(json, "--json");
  if (!charts.empty()) check_output_folder(charts, "--charts");
  const AntialiasingResult r = run_antialiasing_bench(params, bench, [&](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "%s\n", line.c_str());
  });
  if (r.shutter > 0)
    std::printf(
        "antialiasing under the shutter %g, %dx%d, %zu frames, %zu lights, reference embree %d "
        "samples per pixel in (x, y, t)\n",
        r.shutter, r.width, r.height, r.frames, r.lights, r.reference_samples);
  else
    std::printf(
        "antialiasing, %dx%d, %zu frames, %zu lights, reference embree %d samples per pixel\n",
        r.width, r.height, r.frames, r.lights, r.reference_samples);
  std::printf("%-12s %12s %12s %12s %16s\n", "method", "ms/frame", "rmse", "max",
              "events/interval");
  std::printf("%-12s %12.2f %12.3g %12.3g %16.0f\n", "kinetic", r.kinetic.ms_per_frame,
              r.kinetic.rmse, r.kinetic.max_error, r.events_per_interval);
  for (const AntialiasingPoint& p : r.embree) {
    char method[32];
    std::snprintf(method, sizeof method, "embree/%d", p.samples);
    std::printf("%-12s %12.2f %12.3g %12.3g\n", method, p.ms_per_frame, p.rmse, p.max_error);
  }
  if (!json.empty())
    write_file_atomically(json, nlohmann::json({{"antialiasing", r.to_json()}}).dump(2) + "\n");
  if (!charts.empty()) {
    create_output_folder(charts, "--charts");
    const std::string path = (std::filesystem::path(charts) / "antialiasing.png").string();
    write_quality_chart(
        r.shutter > 0 ? "Exact antialiasing under the shutter" : "Exact antialiasing",
        {{r.scene, r.kinetic, r.embree}}, path);
    std::printf("chart: %s\n", path.c_str());
  }
}

}  // namespace kinray
