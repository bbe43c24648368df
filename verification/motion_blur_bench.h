#pragma once
// Equal-quality motion blur benchmark (docs/design.md, "Exact motion blur"): for one scene and
// shutter, the kinetic backend's exact blur and Embree's stratified time sampling at several sample
// counts, each timed per frame and measured against a reference frame (Embree with very many
// samples). Error is the RMSE (and max) over every channel of every pixel, in linear RGB, pooled
// over the frames, but for the pixels of coincident surfaces, which are ties (coincident_fronts.h);
// time per frame is the median wall time of the frames after the first (the first holds the kinetic
// grid's scan conversion and each backend's warm-up; the kinetic init is reported apart).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/job/render_job.h"
#include "verification/quality_point.h"

namespace kinray {

struct MotionBlurBenchParams {
  std::vector<int> samples = {4, 16, 64, 256};  ///< Embree's samples per pixel, one run each
  int reference_samples = 4096;                 ///< the reference frame's samples per pixel
};

using MotionBlurPoint = QualityPoint;

struct MotionBlurResult {
  std::string scene;
  int width = 0, height = 0, reference_samples = 0, order = 0;
  double shutter = 0, kinetic_init_ms = 0;
  size_t frames = 0, triangles = 0;
  size_t lights = 0;  ///< the scene's lights (0: the headlight)
  MotionBlurPoint kinetic;
  /// Where a kinetic frame's time goes, means over the frames after the first: the grid's
  /// events (windows and the gaps between them), the log walks and quadrature, the id and depth
  /// read-out (KineticShutterStats).
  double kinetic_events_ms = 0, kinetic_integrate_ms = 0, kinetic_readout_ms = 0;
  std::vector<MotionBlurPoint> embree;
  /// Pixels of coincident surfaces (coincident_fronts.h), over every frame: set aside as ties
  /// from every method's rmse and max; the kinetic rmse with them kept.
  size_t tie_pixels = 0;
  double kinetic_rmse_with_ties = 0;
  /// {"kinetic": {"ms_per_frame", "rmse", ...}, "embree": [{"samples", "ms_per_frame", "rmse"}...]}
  [[nodiscard]] nlohmann::json to_json() const;
  /// Kinetic error <= Embree's at 256 samples and faster than Embree at 64 (when measured) by
  /// 10x, or by 5x with lights (each shadow ray is a trace for either side).
  [[nodiscard]] bool meets_targets() const;
};

/// Runs the comparison on `params` (its scene, size, frames and --shutter). `log` gets a line per
/// measurement. Throws InputError for bad flags or a shutter of 0.
[[nodiscard]] MotionBlurResult run_motion_blur_bench(
    const RenderParams& params, const MotionBlurBenchParams& bench,
    const std::function<void(const std::string&)>& log);

/// A log-log chart of error against time per frame, a series per scene for Embree and a point per
/// scene for kinetic, written as PNG to `path`.
void write_motion_blur_chart(const std::vector<MotionBlurResult>& results, const std::string& path);

}  // namespace kinray
