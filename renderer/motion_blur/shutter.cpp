#include "renderer/motion_blur/shutter.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "util/input_error.h"

namespace kinray {

void validate(const ShutterParams& params) {
  if (!std::isfinite(params.shutter) || params.shutter < 0 || params.shutter > 1)
    throw InputError("--shutter",
                     "must be a fraction of the frame interval in [0, 1] (0.5 is a "
                     "180-degree shutter), got " +
                         std::to_string(params.shutter));
  if (params.samples < 1 || params.samples > kMaxShutterSamples)
    throw InputError("--shutter-samples", "must lie in 1.." + std::to_string(kMaxShutterSamples) +
                                              ", got " + std::to_string(params.samples));
  if (params.order < 0 || params.order > kMaxShutterOrder)
    throw InputError("--shutter-order", "must lie in 0.." + std::to_string(kMaxShutterOrder) +
                                            " (0: the default), got " +
                                            std::to_string(params.order));
}

std::vector<ShutterWindow> shutter_windows(std::span<const double> frame_times,
                                           std::span<const double> key_times, double shutter) {
  std::vector<ShutterWindow> windows;
  windows.reserve(frame_times.size());
  const size_t n = frame_times.size();
  const double first = key_times.empty() ? -INFINITY : key_times.front();
  const double last = key_times.empty() ? INFINITY : key_times.back();
  for (size_t i = 0; i < n; ++i) {
    const double t = frame_times[i];
    double interval = 0;
    if (n > 1) {
      const double before = i > 0 ? frame_times[i - 1] : t;
      const double after = i + 1 < n ? frame_times[i + 1] : t;
      interval = (i > 0 && i + 1 < n) ? (after - before) / 2 : after - before;
    } else if (key_times.size() > 1) {
      const auto k = std::upper_bound(key_times.begin(), key_times.end(), t);
      const size_t hi = std::clamp<size_t>(size_t(k - key_times.begin()), 1, key_times.size() - 1);
      interval = key_times[hi] - key_times[hi - 1];
    }
    const double half = shutter * interval / 2;
    windows.push_back({std::max(first, t - half), t, std::min(last, t + half)});
  }
  return windows;
}

GaussLegendre gauss_legendre(int order) {
  GaussLegendre rule;
  const int n = std::max(order, 1);
  rule.nodes.resize(size_t(n));
  rule.weights.resize(size_t(n));
  for (int k = 0; k < n; ++k) {
    // Newton on P_n from the Chebyshev-like guess; P_n and P_n' by the three-term recurrence.
    double x = std::cos(M_PI * (k + 0.75) / (n + 0.5)), derivative = 1;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1, p1 = x;
      for (int m = 2; m <= n; ++m) {
        const double p2 = ((2.0 * m - 1) * x * p1 - (m - 1.0) * p0) / m;
        p0 = p1;
        p1 = p2;
      }
      const double p = n == 1 ? x : p1, previous = n == 1 ? 1.0 : p0;
      derivative = n * (x * p - previous) / (x * x - 1);
      const double step = p / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    rule.nodes[size_t(k)] = x;
    rule.weights[size_t(k)] = 2 / ((1 - x * x) * derivative * derivative);
  }
  std::vector<size_t> ascending(static_cast<size_t>(n));
  std::iota(ascending.begin(), ascending.end(), size_t(0));
  std::sort(ascending.begin(), ascending.end(),
            [&](size_t a, size_t b) { return rule.nodes[a] < rule.nodes[b]; });
  rule.cell_lo.resize(size_t(n));
  rule.cell_hi.resize(size_t(n));
  double lo = -1;
  for (size_t k : ascending) {
    rule.cell_lo[k] = lo;
    lo = ascending.back() == k ? 1.0 : lo + rule.weights[k];
    rule.cell_hi[k] = lo;
  }
  return rule;
}

double stratified_time(const ShutterWindow& window, uint32_t pixel, int k, int n, uint64_t seed) {
  // splitmix64 of (seed, pixel, k): a fixed, well-spread jitter per sample.
  uint64_t z = seed * 0x9E3779B97F4A7C15ull + (uint64_t(pixel) << 20) + uint64_t(k);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  const double jitter = double(z >> 11) * 0x1.0p-53;
  return window.open + window.length() * ((k + jitter) / n);
}

}  // namespace kinray
