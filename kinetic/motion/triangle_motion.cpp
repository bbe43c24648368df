#include "kinetic/motion/triangle_motion.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "kinetic/motion/exact_orientation.h"

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
  const Polynomial o = dot(edge_normal(v[0], v[1]), v[2]);
  // Coefficient k of det(a_i + b_i s) sums 6 * C(3, k) products of k motions and 3 - k positions,
  // each at most B^k A^(3-k); the triple product rounds through at most eight operations per
  // term: 32 units of rounding of that sum bound its error generously. When the rounded O cannot
  // be told from zero it is formed exactly (exact_orientation.h): then a degenerate triangle (two
  // vertices equal, or all three on one line) has O exactly zero and covers nothing. A triangle
  // that is not degenerate has some coefficient far above its bound, and costs one triple product.
  double A = 0, B = 0;
  for (const PointMotion& p : v) {
    A = std::max(A, p.a.cwiseAbs().maxCoeff());
    B = std::max(B, p.b.cwiseAbs().maxCoeff());
  }
  constexpr double kUnits = 32 * 6 * 0x1p-53;
  const double bound[4] = {kUnits * A * A * A, kUnits * 3 * A * A * B, kUnits * 3 * A * B * B,
                           kUnits * B * B * B};
  for (size_t k = 0; k < 4; ++k)
    if (std::abs(o.c[k]) > bound[k]) return o;
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
