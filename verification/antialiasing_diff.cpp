#include "verification/antialiasing_diff.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "renderer/antialiasing/pixel_samples.h"
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

AntialiasingTolerance AntialiasingTolerance::for_samples(int samples) {
  const double m = std::sqrt(double(samples));
  return {1 / (m * std::sqrt(m)), 3 / m};
}

bool AntialiasingTolerance::met(const ColorError& e) const {
  return std::sqrt(e.mse) <= rmse && e.max_error <= max_error;
}

void check_reference_samples(int samples) {
  if (sample_grid_side(samples) == 0 || samples > kMaxAaSamples)
    throw InputError("--reference-samples",
                     "the reference's antialiasing samples must be a square in 1.." +
                         std::to_string(kMaxAaSamples) + " (1024, 4096, ...), got " +
                         std::to_string(samples));
}

void run_antialiasing_diff(const RenderParams& params, const AntialiasingDiffOptions& options) {
  if (params.aa != Antialiasing::exact && params.aa_samples <= 1)
    throw InputError("--aa", "the antialiasing diff compares --aa exact or --aa-samples frames");
  const int samples = options.reference_samples;
  check_reference_samples(samples);
  if (!options.report.empty()) check_output_folder(options.report, "--report");
  if (!options.json.empty()) check_output_file(options.json, "--json");
  RenderJob job(params);
  std::unique_ptr<Backend> tested = job.make_backend();
  // The reference supersamples: the job's own dispatch (render_frame) would ask it for --aa exact.
  BackendConfig config = backend_config(params);
  config.aa = Antialiasing::none;
  config.aa_samples = samples;
  std::unique_ptr<Backend> reference = make_backend("embree", job.camera_space(), config);

  // Everything is valid: from here on files are written.
  create_output_folder(options.report, "--report");
  create_output_folder(std::filesystem::path(options.json).parent_path(), "--json");
  const std::filesystem::path report(options.report);
  const AntialiasingTolerance tolerance = AntialiasingTolerance::for_samples(samples);
  nlohmann::json frames = nlohmann::json::array();
  const size_t count = job.frame_times().size();
  Progress progress(count, !params.quiet && Progress::stderr_is_terminal());
  Frame a, b;
  size_t over = 0;
  double worst_rmse = 0, worst_max = 0, squared = 0;
  for (size_t index = 0; index < count; ++index) {
    job.render_frame(*tested, index, a);
    reference->render_supersampled(job.frame_times()[index], b);
    const ColorError error = compare_colors(a, b);
    const double rmse = std::sqrt(error.mse);
    squared += error.mse;
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
  // Pooled over every channel of every pixel of every frame (all frames have the same size).
  const double overall_rmse = count ? std::sqrt(squared / double(count)) : 0;
  const nlohmann::json summary = {
      {"scene", params.scene},
      {"tested", tested->name()},
      {"aa", antialiasing_name(params.aa)},
      {"aa_samples", params.aa_samples},
      {"reference", "embree"},
      {"reference_samples", samples},
      {"tolerance", {{"rmse", tolerance.rmse}, {"max_error", tolerance.max_error}}},
      {"rmse", overall_rmse},
      {"worst_rmse", worst_rmse},
      {"worst_max_error", worst_max},
      {"frames_outside", over},
      {"per_frame", frames}};
  if (!options.json.empty()) write_file_atomically(options.json, summary.dump(2) + "\n");
  if (!options.report.empty())
    write_file_atomically((report / "summary.json").string(), summary.dump(2) + "\n");
  if (!params.quiet)
    std::printf(
        "all frames: rmse %.3g  max %.3g\nreference: embree, %d antialiasing samples per pixel; "
        "tolerance rmse <= %g, max <= %g: %s\n",
        overall_rmse, worst_max, samples, tolerance.rmse, tolerance.max_error,
        over ? "exceeded" : "met");
  if (over > 0)
    throw std::runtime_error(
        std::string(params.aa == Antialiasing::exact
                        ? "diff --aa exact: "
                        : "diff --aa-samples " + std::to_string(params.aa_samples) + ": ") +
        std::to_string(over) + " of " + std::to_string(count) + " frames outside the tolerance");
}

}  // namespace kinray
