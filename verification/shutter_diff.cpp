#include "verification/shutter_diff.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "renderer/output/progress.h"
#include "util/input_error.h"
#include "verification/shutter_error.h"

namespace kinray {
namespace {

std::string numbered(const char* prefix, size_t index) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu.png", prefix, index);
  return name;
}

}  // namespace

void run_shutter_diff(const RenderParams& params, const ShutterDiffOptions& options) {
  const int samples = options.reference_samples;
  if (samples < 1 || samples > kMaxShutterSamples)
    throw InputError("--reference-samples", "must lie in 1.." + std::to_string(kMaxShutterSamples));
  RenderJob job(params);
  std::unique_ptr<Backend> tested = job.make_backend();
  BackendConfig config = backend_config(params);
  config.shutter.samples = samples;
  std::unique_ptr<Backend> reference = make_backend("embree", job.camera_space(), config);

  create_output_folder(options.report, "--report");
  create_output_folder(std::filesystem::path(options.json).parent_path(), "--json");
  const std::filesystem::path report(options.report);
  const ShutterTolerance tolerance;
  nlohmann::json frames = nlohmann::json::array();
  Progress progress(job.frame_times().size(), !params.quiet && Progress::stderr_is_terminal());
  Frame a, b;
  size_t over = 0;
  double worst_rmse = 0, worst_max = 0;
  for (size_t index = 0; index < job.frame_times().size(); ++index) {
    job.render_frame(*tested, index, a);
    job.render_frame(*reference, index, b);
    const ColorError error = compare_colors(a, b);
    const double rmse = std::sqrt(error.mse);
    worst_rmse = std::max(worst_rmse, rmse);
    worst_max = std::max(worst_max, error.max_error);
    const bool met = tolerance.met(error);
    if (!met) ++over;
    if (!options.report.empty()) {
      write_color_png((report / numbered("tested", index)).string(), a);
      write_color_png((report / numbered("reference", index)).string(), b);
      write_error_png(a, b, (report / numbered("error", index)).string());
    }
    frames.push_back({{"frame", index},
                      {"time", job.frame_times()[index]},
                      {"rmse", rmse},
                      {"max_error", error.max_error},
                      {"within_tolerance", met}});
    if (!params.quiet) {
      std::printf("frame %5zu  t=%-10g rmse %.3g  max %.3g%s\n", index, job.frame_times()[index],
                  rmse, error.max_error, met ? "" : "  OUTSIDE TOLERANCE");
      std::fflush(stdout);
    }
    progress.update(index + 1);
  }
  progress.finish();
  const nlohmann::json summary = {
      {"scene", params.scene},
      {"tested", tested->name()},
      {"reference", "embree"},
      {"reference_samples", samples},
      {"shutter", params.shutter.shutter},
      {"tolerance", {{"rmse", tolerance.rmse}, {"max_error", tolerance.max_error}}},
      {"worst_rmse", worst_rmse},
      {"worst_max_error", worst_max},
      {"frames_outside", over},
      {"per_frame", frames}};
  if (!options.json.empty()) write_file_atomically(options.json, summary.dump(2) + "\n");
  if (!options.report.empty())
    write_file_atomically((report / "summary.json").string(), summary.dump(2) + "\n");
  if (!params.quiet)
    std::printf(
        "reference: embree, %d time samples per pixel; tolerance rmse <= %g, max <= %g: %s\n",
        samples, tolerance.rmse, tolerance.max_error, over ? "exceeded" : "met");
  if (over > 0)
    throw std::runtime_error("diff --shutter: " + std::to_string(over) + " of " +
                             std::to_string(job.frame_times().size()) +
                             " frames outside the tolerance");
}

}  // namespace kinray
