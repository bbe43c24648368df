#include "verification/quality_point.h"

#include <algorithm>
#include <cmath>

#include "verification/bench_support.h"
#include "verification/chart.h"
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
                             const std::function<void()>& after_first, const TieMasks& ties) {
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
    const ColorError error =
        compare_colors(frame, reference[index], index < ties.size() ? &ties[index] : nullptr);
    squared += error.mse;
    point.max_error = std::max(point.max_error, error.max_error);
  }
  // The median, not the mean: the machine is shared, and one frame slowed by another process
  // should not move the ratio.
  point.ms_per_frame = median(later_ms);
  point.rmse = std::sqrt(squared / double(job.frame_times().size()));
  return point;
}

void measure_error(const std::vector<Frame>& frames, const std::vector<Frame>& reference,
                   const TieMasks& ties, QualityPoint& point) {
  double squared = 0;
  point.max_error = 0;
  for (size_t index = 0; index < frames.size(); ++index) {
    const ColorError error = compare_colors(frames[index], reference.at(index),
                                            index < ties.size() ? &ties[index] : nullptr);
    squared += error.mse;
    point.max_error = std::max(point.max_error, error.max_error);
  }
  point.rmse = frames.empty() ? 0.0 : std::sqrt(squared / double(frames.size()));
}

void write_quality_chart(const std::string& title, const std::vector<QualityCurve>& curves,
                         const std::string& path) {
  const Color palette[] = {Color(0.1f, 0.3f, 0.8f), Color(0.8f, 0.3f, 0.1f),
                           Color(0.1f, 0.6f, 0.2f), Color(0.6f, 0.1f, 0.6f),
                           Color(0.4f, 0.4f, 0.4f)};
  Chart chart;
  chart.title = curves.size() == 1 ? title + ", " + curves.front().scene : title;
  chart.x_label = "ms per frame";
  chart.y_label = "RMSE against the reference";
  chart.log_x = chart.log_y = true;
  for (size_t s = 0; s < curves.size(); ++s) {
    const QualityCurve& c = curves[s];
    std::string counts;
    if (!c.embree.empty())
      counts = " " + std::to_string(c.embree.front().samples) + ".." +
               std::to_string(c.embree.back().samples) + " spp";
    // One scene: the title names it, and the legend only the methods (a scene's parameters
    // would not fit).
    const std::string name = curves.size() > 1 ? c.scene + " " : "";
    ChartSeries embree{name + "embree" + counts, {}, {}, palette[s % 5], true};
    for (const QualityPoint& p : c.embree) {
      embree.x.push_back(p.ms_per_frame);
      embree.y.push_back(p.rmse);
    }
    chart.series.push_back(embree);
    // A point drawn as a short segment, so the chart's lines show it.
    ChartSeries kinetic{name + "kinetic",
                        {c.kinetic.ms_per_frame * 0.95, c.kinetic.ms_per_frame * 1.05},
                        {c.kinetic.rmse, c.kinetic.rmse},
                        palette[s % 5],
                        false};
    chart.series.push_back(kinetic);
  }
  write_chart_png(chart, path);
}

}  // namespace kinray
