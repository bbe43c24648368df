#include "kinetic/triangle_motion.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "kinetic/exact_orientation.h"

namespace kinray {

namespace {

// (c0 + c1 s + c2 s^2) . (a + b s), a cubic.
Polynomial dot(const EdgeNormal& n, const PointMotion& v) {
  Polynomial f;
  f.degree = 3;
  f.c[0] = n.c0.dot(v.a);
  f.c[1] = n.c0.dot(v.b) + n.c1.dot(v.a);
  f.c[2] = n.c1.dot(v.b) + n.c2.dot(v.a);
  f.c[3] = n.c2.dot(v.b);
  return f;
}

}  // namespace

Polynomial TriangleMotion::orientation() const {
  const Polynomial o1 = dot(edge_normal(v[0], v[1]), v[2]);
  const Polynomial o2 = dot(edge_normal(v[1], v[2]), v[0]);
  const Polynomial o3 = dot(edge_normal(v[2], v[0]), v[1]);
  const Polynomial o = (1.0 / 3.0) * ((o1 + o2) + o3);
  // Coefficient k of det(a_i + b_i s) sums 6 * C(3, k) products of k motions and 3 - k positions,
  // each at most B^k A^(3-k); each triple product rounds through about ten operations, the mean
  // three more: 32 units of rounding of that sum bound the error generously. When the rounded O
  // cannot be told from zero, it is formed exactly (exact_orientation.h). A triangle that is not
  // degenerate has some coefficient far above its bound, so the exact path is for slivers only.
  double A = 0, B = 0;
  for (const PointMotion& p : v) {
    A = std::max(A, p.a.cwiseAbs().maxCoeff());
    B = std::max(B, p.b.cwiseAbs().maxCoeff());
  }
  constexpr double kUnits = 32 * 0x1p-53;
  constexpr std::array<double, 4> kBinomial = {1, 3, 3, 1};
  double power_b = 1;
  for (size_t k = 0; k < 4; ++k) {
    const double bound = kUnits * 6 * kBinomial[k] * power_b * std::pow(A, double(3 - k));
    if (std::abs(o.c[k]) > bound) return o;
    power_b *= B;
  }
  return exact_orientation(*this);
}

TriangleMotion TriangleMotion::rebased(double shift) const {
  TriangleMotion m = *this;
  if (shift != 0)
    for (PointMotion& p : m.v) p.a = p.a + p.b * shift;
  return m;
}

PixelPolynomials pixel_polynomials(const TriangleMotion& m, double x, double y) {
  PixelPolynomials p;
  for (int e = 0; e < 3; ++e) p.edge[e] = m.edge(e).along(x, y);
  p.orientation = m.orientation();
  return p;
}

}  // namespace kinray
