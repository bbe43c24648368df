#pragma once
// Motion blur (docs/design.md, "Exact motion blur"): a frame at time t with shutter S shows, at
// each pixel centre, the time average of the radiance along the centre ray over the frame's shutter
// window. This file fixes the windows of a schedule and holds the pieces every backend's time
// average shares: Gauss-Legendre rules, stratified sample times, and the average itself.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "scenes/scene.h"

namespace kinray {

/// The --shutter flags, one field each; shutter == 0 renders sharp frames and changes nothing.
struct ShutterParams {
  double shutter = 0;  ///< --shutter S: open for this fraction of the frame interval, in [0, 1]
  int samples = 16;    ///< --shutter-samples N: time samples per pixel of the sampling backends
  int order = 0;       ///< --shutter-order: kinetic Gauss-Legendre nodes per interval (0: default)
  [[nodiscard]] bool enabled() const { return shutter > 0; }
};

/// The kinetic backend's Gauss-Legendre order when --shutter-order is 0 (see docs/motion_blur.md).
inline constexpr int kDefaultShutterOrder = 4;
/// The kinetic backend's least order on a textured front (its texels slide under the pixel).
inline constexpr int kTexturedShutterOrder = 16;
inline constexpr int kMaxShutterOrder = 16;
inline constexpr int kMaxShutterSamples = 65536;

/// Throws InputError naming the flag: S outside [0, 1], N outside 1..65536, order outside 0..16.
void validate(const ShutterParams& params);

/// The time a frame's shutter is open: [open, close], open <= time <= close.
struct ShutterWindow {
  double open = 0, time = 0, close = 0;
  [[nodiscard]] double length() const { return close - open; }
};

/// The window of every frame: centred on t_i, S times the frame interval long, where the interval
/// of frame i is (t_{i+1} - t_{i-1}) / 2 (one-sided at the first and last frame, so a regular
/// schedule's interval is its spacing), and of a lone frame the key interval of `key_times` that
/// holds it. Windows are clipped to [key_times.front(), key_times.back()] (the scene's shot, where
/// its motion is defined), and may overlap when the spacing is irregular.
[[nodiscard]] std::vector<ShutterWindow> shutter_windows(std::span<const double> frame_times,
                                                         std::span<const double> key_times,
                                                         double shutter);

/// Gauss-Legendre nodes and weights on [-1, 1] (weights sum to 2), by Newton's method on P_n.
struct GaussLegendre {
  std::vector<double> nodes, weights;
  /// Node k's cell [cell_lo[k], cell_hi[k]] of [-1, 1]: the cells tile it in the nodes' order,
  /// each as long as its node's weight, and each holds its node (the separation theorem of
  /// Chebyshev, Markov and Stieltjes). A textured front's node averages its texture over its
  /// cell (for_each_quadrature_cell).
  std::vector<double> cell_lo, cell_hi;
};
[[nodiscard]] GaussLegendre gauss_legendre(int order);

/// Calls visit(t, weight, next, lo, hi) for each node of `rule` over [t0, t1] (t0 < t1), the
/// weights shares of a window of length `length`, [lo, hi] the node's cell on its piece
/// (GaussLegendre::cell_lo, cell_hi). The shading is smooth between the keys of the front's
/// object, not across them (its vertices and normals turn there): each piece between the `keys`
/// (sorted) inside [t0, t1] gets its own rule, and the node's piece lies in
/// [keys[next - 1], keys[next]] (next = 0 or keys.size(): before or after the keys).
template <class Visit>
void for_each_quadrature_cell(std::span<const double> keys, const GaussLegendre& rule, double t0,
                              double t1, double length, Visit&& visit) {
  const double share = (t1 - t0) / length;
  auto key = std::upper_bound(keys.begin(), keys.end(), t0);
  for (double a = t0; a < t1;) {
    const size_t next = size_t(key - keys.begin());
    const double b = key != keys.end() && *key < t1 ? *key++ : t1;
    const double middle = (a + b) / 2, half = (b - a) / 2;
    for (size_t k = 0; k < rule.nodes.size(); ++k)
      visit(middle + half * rule.nodes[k], share * (half / (t1 - t0)) * rule.weights[k], next,
            std::max(a, middle + half * rule.cell_lo[k]),
            std::min(b, middle + half * rule.cell_hi[k]));
    a = b;
  }
}

/// for_each_quadrature_cell without the cells: visit(t, weight, next).
template <class Visit>
void for_each_quadrature_node(std::span<const double> keys, const GaussLegendre& rule, double t0,
                              double t1, double length, Visit&& visit) {
  for_each_quadrature_cell(
      keys, rule, t0, t1, length,
      [&](double t, double w, size_t next, double, double) { visit(t, w, next); });
}

/// Time of stratified sample k of n in `window` for `pixel`: stratum k, jittered by a hash of
/// (pixel, k, seed), so every backend and every run draws the same times.
[[nodiscard]] double stratified_time(const ShutterWindow& window, uint32_t pixel, int k, int n,
                                     uint64_t seed);

/// A weighted average of colours that returns a colour exactly when every sample was that colour
/// (so a pixel nothing moves over renders exactly as the sharp frame does).
class ColorAverage {
 public:
  void add(const Color& c, double weight) {
    if (m_weight == 0) m_first = c;
    m_uniform = m_uniform && c == m_first;
    m_sum += Eigen::Vector3d(c.cast<double>()) * weight;
    m_weight += weight;
  }
  [[nodiscard]] Color result() const {
    if (m_weight <= 0) return Color::Zero();
    return m_uniform ? m_first : Color((m_sum / m_weight).cast<float>());
  }

 private:
  Eigen::Vector3d m_sum = Eigen::Vector3d::Zero();
  double m_weight = 0;
  Color m_first = Color::Zero();
  bool m_uniform = true;
};

}  // namespace kinray
