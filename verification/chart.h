#pragma once
// Line charts as PNG images, drawn with OpenCV, for the benchmark sweeps: no plotting library is
// in Debian's C++ stack that fits, and a chart of a few series needs only lines and labels.
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace kinray {

struct ChartSeries {
  std::string label;
  std::vector<double> x, y;  ///< same length; points with y <= 0 on a log axis are skipped
  Eigen::Vector3f color = Eigen::Vector3f(0.1f, 0.3f, 0.8f);  ///< linear RGB in [0, 1]
  bool dashed = false;
};

struct Chart {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<ChartSeries> series;
  std::optional<double> marker_x;  ///< a vertical marker (e.g. the break-even point)
  std::string marker_label;
};

/// Draws `chart` into a `width` x `height` PNG at `path`. Throws InputError when the file
/// cannot be written or the chart has no finite point.
void write_chart_png(const Chart& chart, const std::string& path, int width = 960, int height = 600);

}  // namespace kinray
