#include "verification/chart.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "util/input_error.h"

namespace kinray {
namespace {

cv::Scalar bgr(const Eigen::Vector3f& c) {
  return cv::Scalar(255 * c.z(), 255 * c.y(), 255 * c.x());
}

/// One axis: data range mapped to a pixel range, linear or log10.
struct Axis {
  double lo = 0, hi = 1;
  bool log = false;
  [[nodiscard]] double map(double v) const { return log ? std::log10(v) : v; }
  [[nodiscard]] double fraction(double v) const { return (map(v) - lo) / (hi - lo); }
};

Axis make_axis(const std::vector<double>& values, bool log) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (double v : values) {
    if (!std::isfinite(v) || (log && v <= 0)) continue;
    const double m = log ? std::log10(v) : v;
    lo = std::min(lo, m);
    hi = std::max(hi, m);
  }
  Axis axis;
  axis.log = log;
  if (!std::isfinite(lo)) return axis;
  if (hi - lo < 1e-9) {
    lo -= log ? 0.5 : std::max(1.0, std::abs(lo) * 0.1);
    hi += log ? 0.5 : std::max(1.0, std::abs(hi) * 0.1);
  }
  const double pad = (hi - lo) * 0.05;
  axis.lo = log ? std::floor(lo - pad) : lo - pad;
  axis.hi = log ? std::ceil(hi + pad) : hi + pad;
  if (!log && lo >= 0 && axis.lo < 0) axis.lo = 0;
  return axis;
}

std::string tick_label(double v) {
  char text[32];
  if (std::abs(v) >= 1e6) std::snprintf(text, sizeof text, "%gM", v / 1e6);
  else if (std::abs(v) >= 1e4) std::snprintf(text, sizeof text, "%gk", v / 1e3);
  else std::snprintf(text, sizeof text, "%g", v);
  return text;
}

std::vector<double> ticks(const Axis& axis) {
  std::vector<double> result;
  if (axis.log) {
    for (double e = std::ceil(axis.lo); e <= axis.hi + 1e-9; e += 1) {
      result.push_back(std::pow(10.0, e));
      if (axis.hi - axis.lo <= 2.5 && e + std::log10(3.0) <= axis.hi) result.push_back(3 * std::pow(10.0, e));
    }
    return result;
  }
  const double span = axis.hi - axis.lo;
  const double raw = span / 6;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (raw <= m * magnitude) {
      step = m * magnitude;
      break;
    }
  for (double v = std::ceil(axis.lo / step) * step; v <= axis.hi + 1e-9 * span; v += step) result.push_back(v);
  return result;
}

}  // namespace

void write_chart_png(const Chart& chart, const std::string& path, int width, int height) {
  std::vector<double> xs, ys;
  for (const ChartSeries& s : chart.series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  if (chart.marker_x) xs.push_back(*chart.marker_x);
  const Axis ax = make_axis(xs, chart.log_x), ay = make_axis(ys, chart.log_y);
  if (xs.empty() || ys.empty()) throw InputError(path, "the chart '" + chart.title + "' has no data");

  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  const int left = 90, right = width - 230, top = 64, bottom = height - 70;
  auto px = [&](double x) { return left + int(std::lround(ax.fraction(x) * (right - left))); };
  auto py = [&](double y) { return bottom - int(std::lround(ay.fraction(y) * (bottom - top))); };
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const cv::Scalar ink(40, 40, 40), grid(225, 225, 225);

  for (double t : ticks(ax)) {
    cv::line(image, {px(t), top}, {px(t), bottom}, grid, 1);
    const std::string label = tick_label(t);
    const cv::Size size = cv::getTextSize(label, font, 0.45, 1, nullptr);
    cv::putText(image, label, {px(t) - size.width / 2, bottom + 20}, font, 0.45, ink, 1, cv::LINE_AA);
  }
  for (double t : ticks(ay)) {
    cv::line(image, {left, py(t)}, {right, py(t)}, grid, 1);
    const std::string label = tick_label(t);
    const cv::Size size = cv::getTextSize(label, font, 0.45, 1, nullptr);
    cv::putText(image, label, {left - 8 - size.width, py(t) + 5}, font, 0.45, ink, 1, cv::LINE_AA);
  }
  cv::rectangle(image, {left, top}, {right, bottom}, ink, 1);
  cv::putText(image, chart.title, {left, 26}, font, 0.6, ink, 1, cv::LINE_AA);
  const cv::Size xsize = cv::getTextSize(chart.x_label, font, 0.5, 1, nullptr);
  cv::putText(image, chart.x_label, {(left + right - xsize.width) / 2, bottom + 48}, font, 0.5, ink, 1, cv::LINE_AA);
  cv::putText(image, chart.y_label, {8, top - 12}, font, 0.45, ink, 1, cv::LINE_AA);

  if (chart.marker_x && (!chart.log_x || *chart.marker_x > 0)) {
    const int x = px(*chart.marker_x);
    for (int y = top; y < bottom; y += 10) cv::line(image, {x, y}, {x, std::min(y + 5, bottom)}, cv::Scalar(0, 140, 0), 2);
    cv::putText(image, chart.marker_label, {x + 6, top + 18}, font, 0.45, cv::Scalar(0, 120, 0), 1, cv::LINE_AA);
  }
  int legend_y = top + 10;
  for (const ChartSeries& s : chart.series) {
    const cv::Scalar color = bgr(s.color);
    std::vector<cv::Point> points;
    for (size_t k = 0; k < s.x.size() && k < s.y.size(); ++k) {
      if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k])) continue;
      if ((chart.log_x && s.x[k] <= 0) || (chart.log_y && s.y[k] <= 0)) continue;
      points.emplace_back(px(s.x[k]), py(s.y[k]));
    }
    // A solid or dashed segment, so the legend shows the same stroke as the series.
    auto stroke = [&](cv::Point2d a, cv::Point2d b) {
      if (!s.dashed) {
        cv::line(image, a, b, color, 2, cv::LINE_AA);
        return;
      }
      const double length = cv::norm(b - a);
      for (double d = 0; d < length; d += 12) {
        const cv::Point2d p = a + (b - a) * (d / length), q = a + (b - a) * (std::min(d + 6, length) / length);
        cv::line(image, p, q, color, 2, cv::LINE_AA);
      }
    };
    for (size_t k = 1; k < points.size(); ++k) stroke(points[k - 1], points[k]);
    for (const cv::Point& p : points) cv::circle(image, p, 3, color, cv::FILLED, cv::LINE_AA);
    stroke(cv::Point2d(right + 15, legend_y), cv::Point2d(right + 45, legend_y));
    cv::putText(image, s.label, {right + 52, legend_y + 5}, font, 0.45, ink, 1, cv::LINE_AA);
    legend_y += 22;
  }
  if (!cv::imwrite(path, image)) throw InputError(path, "cannot write the chart");
}

}  // namespace kinray
