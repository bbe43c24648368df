#pragma once
// The depth order of two triangles that share an edge, where both cover a pixel (a fold: they
// overlap on the screen). With A = (p, q, a) and B holding the same edge, the depth
// certificate's product difference factors:
//     N_B D_A - N_A D_B = kappa det(q - p, a - p, b - p) ((p x q) . d),
// kappa = -1 when B runs along the edge from q to p (a consistently wound mesh), +1 when from p
// to q (Binet-Cauchy on (N_B, D_A) - (N_A, D_B): both plane normals are perpendicular to q - p, so
// their cross product is det(q - p, a - p, b - p) (q - p)). While A covers the pixel,
// (p x q) . d has the sign of D_A (the sign rule), so the certificate sign(D_A D_B) (N_B D_A -
// N_A D_B) has the sign of sign(D_B) kappa det(q - p, a - p, b - p): the pair's order changes
// only where the two triangles become coplanar, whatever the pixel. The degree-5 product
// difference instead vanishes where the pixel crosses the shared edge, at the very instant one of
// the two leaves the pixel: a root that is no change of order, whose neighbourhood sent 55% of
// these certificates to exact arithmetic (Testwuson) and fired swaps a few ulps before the
// coverage events that end them.
#include <array>
#include <cstdint>
#include <optional>

#include "kinetic/core/polynomial.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {

/// Where triangle b meets triangle a along a shared edge: a's vertex order (p, q, a) from index
/// `first` of a (p = a[first], q = a[first + 1]), b's third vertex, and kappa.
struct SharedEdge {
  int first = 0;    ///< a's index of p
  int b_other = 0;  ///< b's index of its vertex off the edge
  int kappa = 0;    ///< -1: b runs from q to p; +1: from p to q
};

/// The shared edge of two triangles (global vertex ids), if they share exactly one.
[[nodiscard]] inline std::optional<SharedEdge> shared_edge(const std::array<uint32_t, 3>& a,
                                                           const std::array<uint32_t, 3>& b) {
  for (int i = 0; i < 3; ++i) {
    const uint32_t p = a[size_t(i)], q = a[size_t((i + 1) % 3)];
    for (int j = 0; j < 3; ++j) {
      if (b[size_t(j)] != p) continue;
      const uint32_t next = b[size_t((j + 1) % 3)], before = b[size_t((j + 2) % 3)];
      if (before == q && next != q) return SharedEdge{i, (j + 1) % 3, -1};
      if (next == q && before != q) return SharedEdge{i, (j + 2) % 3, 1};
    }
  }
  return std::nullopt;
}

/// det(q - p, a - p, b - p) of the four moving vertices: a cubic in the motions' local time.
[[nodiscard]] inline Polynomial fold_volume(const PointMotion& p, const PointMotion& q,
                                            const PointMotion& a, const PointMotion& b) {
  std::array<Polynomial, 3> e, alpha, beta;  // the three differences, linear per coordinate
  for (int k = 0; k < 3; ++k) {
    e[size_t(k)] = Polynomial{q.a[k] - p.a[k], q.b[k] - p.b[k]};
    alpha[size_t(k)] = Polynomial{a.a[k] - p.a[k], a.b[k] - p.b[k]};
    beta[size_t(k)] = Polynomial{b.a[k] - p.a[k], b.b[k] - p.b[k]};
  }
  Polynomial volume;
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    const Polynomial cross =
        alpha[size_t(i)] * beta[size_t(j)] - alpha[size_t(j)] * beta[size_t(i)];
    volume = volume + e[size_t(k)] * cross;
  }
  return volume;
}

}  // namespace kinray
