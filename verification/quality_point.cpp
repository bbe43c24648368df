#include "verification/quality_point.h"

#include <algorithm>
#include <cmath>

#include "verification/bench_support.h"
#include "verification/image_diff.h"

namespace kinray {
nlohmann::json QualityPoint::to_json() const {
  return {{"samples", samples},
          {"ms_per_frame", ms_per_frame},
          {"rmse", rmse},
          {"max_error", max_error}};
}

QualityPoint measure_quality(const RenderJob& job,
                             const std::function<void(size_t, Frame&)>& render,
                             const std::vector<Frame>& reference, int samples, double* first_ms,
                             const std::function<void()>& after_first) {
  QualityPoint point;
  point.samples = samples;
  Frame frame;
  double squared = 0;
  std::vector<double> later_ms;
  for (size_t index = 0; index < job.frame_times().size(); ++index) {
    const double start = now_ms();
    render(index, frame);
    const double ms = now_ms() - start;
    if (index == 0 && first_ms) *first_ms = ms;
    if (index == 0 && after_first) after_first();
    if (index > 0 || job.frame_times().size() == 1) later_ms.push_back(ms);
    const ColorError error = compare_colors(frame, reference[index]);
    squared += error.mse;
    point.max_error = std::max(point.max_error, error.max_error);
  }
  // The median, not the mean: the machine is shared, and one frame slowed by another process
  // should not move the ratio.
  point.ms_per_frame = median(later_ms);
  point.rmse = std::sqrt(squared / double(job.frame_times().size()));
  return point;
}

}  // namespace kinray
