#include "verification/antialiasing_diff.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "util/input_error.h"
#include "verification/color_diff.h"

namespace kinray {
AntialiasingTolerance AntialiasingTolerance::for_samples(int samples) {
  const double m = std::sqrt(double(samples));
  AntialiasingTolerance tolerance;
  tolerance.rmse = 1 / (m * std::sqrt(m));
  tolerance.max_error = 3 / m;
  return tolerance;
}

void check_reference_samples(int samples) {
  if (!is_aa_sample_count(samples))
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
  const AntialiasingTolerance tolerance = AntialiasingTolerance::for_samples(samples);
  const ColorDiffFrames diff = diff_frames_by_color(
      job, *tested,
      [&](size_t index, Frame& frame) {
        // Under the shutter the job renders the window: samples in (x, y, t).
        if (params.shutter.enabled())
          job.render_frame(*reference, index, frame);
        else
          reference->render_supersampled(job.frame_times()[index], frame);
      },
      tolerance, options.report, params.quiet);
  nlohmann::json summary = {
      {"scene", params.scene},
      {"tested", tested->name()},
      {"aa", antialiasing_name(params.aa)},
      {"aa_samples", params.aa_samples},
      {"lights", job.scene().lights.size()},
      {"reference", "embree"},
      {"reference_samples", samples},
      {"tolerance", {{"rmse", tolerance.rmse}, {"max_error", tolerance.max_error}}},
      {"rmse", diff.rmse},
      {"worst_rmse", diff.worst_rmse},
      {"worst_max_error", diff.worst_max_error},
      {"frames_outside", diff.outside},
      {"per_frame", diff.per_frame}};
  if (params.shutter.enabled()) summary["shutter"] = params.shutter.shutter;
  if (!options.json.empty()) write_file_atomically(options.json, summary.dump(2) + "\n");
  if (!options.report.empty())
    write_file_atomically((std::filesystem::path(options.report) / "summary.json").string(),
                          summary.dump(2) + "\n");
  if (!params.quiet)
    std::printf(
        "all frames: rmse %.3g  max %.3g\nreference: embree, %d antialiasing samples per pixel%s; "
        "tolerance rmse <= %g, max <= %g: %s\n",
        diff.rmse, diff.worst_max_error, samples, params.shutter.enabled() ? " in (x, y, t)" : "",
        tolerance.rmse, tolerance.max_error, diff.outside ? "exceeded" : "met");
  if (diff.outside > 0)
    throw std::runtime_error(
        std::string(params.aa == Antialiasing::exact
                        ? "diff --aa exact: "
                        : "diff --aa-samples " + std::to_string(params.aa_samples) + ": ") +
        std::to_string(diff.outside) + " of " + std::to_string(job.frame_times().size()) +
        " frames outside the tolerance");
}

}  // namespace kinray
