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
#include "util/input_error.h"
#include "verification/coincident_fronts.h"
#include "verification/color_diff.h"
#include "verification/shutter_error.h"

namespace kinray {
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
  const ShutterTolerance tolerance;
  // Coincident surfaces flicker in every renderer: those pixels are ties, set aside as the sharp
  // diff sets them aside (coincident_fronts.h).
  const ColorDiffFrames diff = diff_frames_by_color(
      job, *tested, [&](size_t index, Frame& frame) { job.render_frame(*reference, index, frame); },
      tolerance, options.report, params.quiet,
      [&](size_t index, const Frame& a, const Frame& b) {
        return coincident_fronts(job.camera_space(), job.shutter_windows()[index], a, b);
      });
  const nlohmann::json summary = {
      {"scene", params.scene},
      {"tested", tested->name()},
      {"reference", "embree"},
      {"reference_samples", samples},
      {"shutter", params.shutter.shutter},
      {"tolerance", {{"rmse", tolerance.rmse}, {"max_error", tolerance.max_error}}},
      {"worst_rmse", diff.worst_rmse},
      {"worst_max_error", diff.worst_max_error},
      {"frames_outside", diff.outside},
      {"ties", diff.ties},
      {"per_frame", diff.per_frame}};
  if (!options.json.empty()) write_file_atomically(options.json, summary.dump(2) + "\n");
  if (!options.report.empty())
    write_file_atomically((std::filesystem::path(options.report) / "summary.json").string(),
                          summary.dump(2) + "\n");
  if (!params.quiet)
    std::printf(
        "reference: embree, %d time samples per pixel; tolerance rmse <= %g, max <= %g: %s%s\n",
        samples, tolerance.rmse, tolerance.max_error, diff.outside ? "exceeded" : "met",
        diff.ties > 0 ? (" (" + std::to_string(diff.ties) +
                         " pixels of coincident surfaces set aside as ties)")
                            .c_str()
                      : "");
  if (diff.outside > 0)
    throw std::runtime_error("diff --shutter: " + std::to_string(diff.outside) + " of " +
                             std::to_string(job.frame_times().size()) +
                             " frames outside the tolerance");
}

}  // namespace kinray
