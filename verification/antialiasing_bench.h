#pragma once
// Equal-quality antialiasing benchmark (docs/verification.md, "Antialiasing"): for one scene, the
// kinetic backend's exact antialiasing (--aa exact) and Embree's stratified supersampling at
// several sample counts, each timed per frame in the same process and measured against a
// reference frame (Embree with very many samples). Error is the RMSE (and max) over every channel
// of every pixel, in linear RGB, pooled over the frames; time per frame is the median wall time of
// the frames after the first (the first holds the kinetic grid's scan conversion, the square
// sets' construction and each backend's warm-up). Mirrors motion_blur_bench.h. Under the shutter
// (params.shutter) every frame is its window's: the kinetic space-time box filter against Embree's
// samples in (x, y, t) (one sample: the centre ray's motion blur at --shutter-samples times).
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/job/render_job.h"
#include "verification/quality_point.h"

namespace kinray {

struct AntialiasingBenchParams {
  std::vector<int> samples = {1, 4, 16, 64, 256, 1024};  ///< Embree's samples per pixel (squares)
  int reference_samples = 4096;  ///< the reference frame's samples per pixel (a square)
};

using AntialiasingPoint = QualityPoint;

struct AntialiasingResult {
  std::string scene;
  int width = 0, height = 0, reference_samples = 0;
  double shutter = 0;  ///< the shutter of every frame (0: sharp frames)
  size_t frames = 0, triangles = 0;
  size_t lights = 0;  ///< the scene's (or --light's): every method shades them with shadow rays
  double kinetic_init_ms = 0;  ///< the first kinetic frame's time beyond the median
  /// The square sets' events of the timed frames (after the first) per keyframe interval they
  /// span: the cost of keeping the sets that no sample count has.
  double events_per_interval = 0;
  AntialiasingPoint kinetic;
  std::vector<AntialiasingPoint> embree;
  /// {"lights", "kinetic": {"ms_per_frame", "rmse", "max_error", "events_per_interval", ...},
  ///  "embree": [{"samples", "ms_per_frame", "rmse", "max_error"}, ...], ...; "shutter" when
  ///  the frames are blurred}
  [[nodiscard]] nlohmann::json to_json() const;
};

/// Runs the comparison on `params` (its scene, size, frames; params.aa must be exact). `log` gets
/// a line per measurement. Throws InputError naming the flag for bad counts (not squares).
[[nodiscard]] AntialiasingResult run_antialiasing_bench(
    const RenderParams& params, const AntialiasingBenchParams& bench,
    const std::function<void(const std::string&)>& log);

/// The keyframe intervals of `keys` that [a, b] spans, counting partial intervals by the fraction
/// covered (0 when a == b or there are fewer than two keys).
[[nodiscard]] double keyframe_intervals(const std::vector<double>& keys, double a, double b);

}  // namespace kinray
