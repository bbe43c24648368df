#include "kinetic/triangle_motion.h"

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
  return (1.0 / 3.0) * ((o1 + o2) + o3);
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
