#pragma once
// One point of an equal-quality comparison (`bench --shutter`, `bench --aa`): a method's time per
// frame and its error against a densely sampled reference, measured over the same frames.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/frame.h"
#include "renderer/job/render_job.h"

namespace kinray {

struct QualityPoint {
  int samples = 0;  ///< 0: the kinetic backend
  double ms_per_frame = 0, rmse = 0, max_error = 0;
  /// {"samples", "ms_per_frame", "rmse", "max_error"}.
  [[nodiscard]] nlohmann::json to_json() const;
};

/// Per frame, a mask of the pixels a comparison sets aside as ties (empty: none).
using TieMasks = std::vector<std::vector<uint8_t>>;

/// Renders every frame of `job` with render(index, frame), timing each, and measures it against
/// `reference` (one frame per frame time), but for the pixels `ties` sets aside. ms_per_frame is
/// the median of the frames after the first (the first pays a build or an initialisation, whose
/// time goes to `first_ms`); `after_first`, when given, runs once the first frame is rendered (to
/// read counters then).
[[nodiscard]] QualityPoint measure_quality(const RenderJob& job,
                                           const std::function<void(size_t, Frame&)>& render,
                                           const std::vector<Frame>& reference, int samples,
                                           double* first_ms,
                                           const std::function<void()>& after_first = {},
                                           const TieMasks& ties = {});

/// point.rmse and point.max_error of `frames` against `reference`, pooled over the frames, but
/// for the pixels `ties` sets aside.
void measure_error(const std::vector<Frame>& frames, const std::vector<Frame>& reference,
                   const TieMasks& ties, QualityPoint& point);

/// One scene's comparison: the kinetic point and Embree's at each sample count.
struct QualityCurve {
  std::string scene;
  QualityPoint kinetic;
  std::vector<QualityPoint> embree;
};

/// A PNG chart of error against time per frame, both axes logarithmic: each scene's Embree
/// points as a line over its sample counts, its kinetic point as a short segment in the same
/// colour.
void write_quality_chart(const std::string& title, const std::vector<QualityCurve>& curves,
                         const std::string& path);

}  // namespace kinray
