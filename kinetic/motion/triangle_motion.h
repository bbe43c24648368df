#pragma once
// The polynomials of a moving triangle on one flightplan segment (docs/design.md, "Certificates and
// their polynomials"). Every vertex moves as p(s) = a + b s in the local time s = t - origin of its
// segment, so
//   - the edge function E_pq(d) = (p x q) . d is quadratic in s,
//   - the orientation O = det(v0, v1, v2) is cubic,
//   - a vertex's side of the row plane Pi_j, n_j . v = v.y - y_j v.z, is linear,
//   - the depth along d is z = O / D with D = (e1 x e2) . d = E_01 + E_12 + E_20, quadratic.
// Every caller (initialisation, events, audit) builds these the same way from the same inputs, so
// the structure and its certificates agree bit for bit.
#include <algorithm>
#include <array>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "kinetic/core/polynomial.h"

namespace kinray {

/// p(s) = a + b s.
struct PointMotion {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  [[nodiscard]] Eigen::Vector3d at(double s) const { return a + b * s; }
};

/// The normal of the plane through the eye and a moving edge: p(s) x q(s) = c0 + c1 s + c2 s^2.
struct EdgeNormal {
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c1 = Eigen::Vector3d::Zero(),
                  c2 = Eigen::Vector3d::Zero();
  /// E(d)'s coefficients (lowest first) for d = (x, y, 1): every user of an edge function along
  /// a ray forms them so, and gets the same bits.
  [[nodiscard]] std::array<double, 3> along_coefficients(double x, double y) const {
    return {c0.x() * x + c0.y() * y + c0.z(), c1.x() * x + c1.y() * y + c1.z(),
            c2.x() * x + c2.y() * y + c2.z()};
  }
  /// E(d) for d = (x, y, 1), a quadratic in s.
  [[nodiscard]] Polynomial along(double x, double y) const {
    const std::array<double, 3> e = along_coefficients(x, y);
    Polynomial f;
    f.degree = 2;
    std::copy(e.begin(), e.end(), f.c.begin());
    return f;
  }
  /// Component k (0: x, 1: y, 2: z) of p x q, a quadratic in s.
  [[nodiscard]] Polynomial component(int k) const {
    Polynomial f;
    f.degree = 2;
    f.c[0] = c0[k];
    f.c[1] = c1[k];
    f.c[2] = c2[k];
    return f;
  }
  /// The normal of the same edge taken the other way, q x p: the exact negation.
  [[nodiscard]] EdgeNormal reversed() const { return EdgeNormal{-c0, -c1, -c2}; }
  /// The edge function along the symbolically perturbed ray d' = (x + eps, y + eps^2, 1):
  /// E(d') = E(d) + eps n_x + eps^2 n_y, whose sign just after s is the sign of the first of
  /// E(d), n_x, n_y that is not the zero polynomial. Returns that polynomial: it is the one whose
  /// sign changes are events. It is zero only when p x q vanishes on the whole segment (the edge's
  /// line passes through the eye).
  [[nodiscard]] Polynomial perturbed(double x, double y) const {
    const Polynomial e = along(x, y);
    if (!e.is_zero()) return e;
    const Polynomial nx = component(0);
    return nx.is_zero() ? component(1) : nx;
  }
};

/// p x q; exactly antisymmetric (edge_normal(q, p) is the negation) and exactly zero for p == q.
[[nodiscard]] inline EdgeNormal edge_normal(const PointMotion& p, const PointMotion& q) {
  EdgeNormal n;
  n.c0 = p.a.cross(q.a);
  n.c1 = p.a.cross(q.b) + p.b.cross(q.a);
  n.c2 = p.b.cross(q.b);
  return n;
}

/// The side of row plane Pi_j (normal (0, 1, -y)) that v is on: n_j . v(s), linear in s.
[[nodiscard]] inline Polynomial row_side(const PointMotion& v, double y) {
  Polynomial f;
  f.degree = 1;
  f.c[0] = v.a.y() - y * v.a.z();
  f.c[1] = v.b.y() - y * v.b.z();
  return f;
}

/// Where the boundary point of edge pq on row plane Pi_j (normal (0, 1, -y)) lies in depth: its
/// z has the sign of sigma (p.z (n.q) - q.z (n.p)), sigma = sign(n.q - n.p) constant while the
/// edge crosses the plane. Returns p.z (n.q) - q.z (n.p), a quadratic.
[[nodiscard]] inline Polynomial boundary_depth(const PointMotion& p, const PointMotion& q, double y) {
  const Polynomial side_p = row_side(p, y), side_q = row_side(q, y);
  Polynomial pz, qz;
  pz.degree = qz.degree = 1;
  pz.c[0] = p.a.z();
  pz.c[1] = p.b.z();
  qz.c[0] = q.a.z();
  qz.c[1] = q.b.z();
  return pz * side_q - qz * side_p;
}

/// Edges are numbered by their first vertex: edge e runs from v[e] to v[(e + 1) % 3].
inline constexpr int kEdgeStart[3] = {0, 1, 2};
inline constexpr int kEdgeEnd[3] = {1, 2, 0};

/// A triangle's three vertex motions on one segment, in the segment's local time.
struct TriangleMotion {
  std::array<PointMotion, 3> v;

  [[nodiscard]] EdgeNormal edge(int e) const { return edge_normal(v[kEdgeStart[e]], v[kEdgeEnd[e]]); }
  /// O(s) = det(v0, v1, v2), a cubic; exactly zero when the triangle is degenerate all segment
  /// long (two vertices equal, or three on one line): such a triangle covers nothing.
  [[nodiscard]] Polynomial orientation() const;
  /// The same motion in the local time s' = s - shift (re-centred at origin + shift).
  [[nodiscard]] TriangleMotion rebased(double shift) const;
};

/// The four polynomials of the sign rule and the depth at one pixel-centre ray.
struct PixelPolynomials {
  std::array<Polynomial, 3> edge;  ///< E_01, E_12, E_20 along d
  Polynomial orientation;          ///< O (independent of d)
  /// D = E_01 + E_12 + E_20: the depth denominator, of the sign of O wherever the ray pierces.
  [[nodiscard]] Polynomial denominator() const { return edge[0] + edge[1] + edge[2]; }
};
[[nodiscard]] PixelPolynomials pixel_polynomials(const TriangleMotion& m, double x, double y);

/// N and D of one triangle along the ray (x, y, 1), in the local time of its motion.
struct DepthPolynomials {
  Polynomial numerator;    ///< det(v0, v1, v2) = (v0 x v1) . v2, cubic
  Polynomial denominator;  ///< ((v1 - v0) x (v2 - v0)) . d, quadratic
};

/// N (cubic) and D (quadratic) of a triangle along a pixel's ray as plain coefficients, lowest
/// first: what the apart test reads, without the zeroed Polynomials (80 bytes each) that the full
/// certificate needs only when the test cannot decide.
struct DepthCoefficients {
  std::array<double, 4> n;  ///< N's
  std::array<double, 3> d;  ///< D's
  /// N and D as the Polynomials of depth_polynomials (degrees 3 and 2).
  [[nodiscard]] DepthPolynomials polynomials() const {
    DepthPolynomials p;
    p.numerator.degree = 3;
    std::copy(n.begin(), n.end(), p.numerator.c.begin());
    p.denominator.degree = 2;
    std::copy(d.begin(), d.end(), p.denominator.c.begin());
    return p;
  }
  /// Horner's values, as Polynomial's operator() computes them at these degrees.
  [[nodiscard]] double numerator(double s) const {
    return ((n[3] * s + n[2]) * s + n[1]) * s + n[0];
  }
  [[nodiscard]] double denominator(double s) const { return (d[2] * s + d[1]) * s + d[0]; }
};

/// The part of N and D that does not depend on the ray: N itself and the normal (e1 x e2) whose
/// along(x, y) is D.
struct DepthParts {
  Polynomial numerator;
  EdgeNormal normal;
};
[[nodiscard]] inline DepthParts depth_parts(const TriangleMotion& m) {
  const EdgeNormal n01 = edge_normal(m.v[0], m.v[1]);
  const PointMotion& v2 = m.v[2];
  DepthParts p;
  p.numerator.degree = 3;
  p.numerator.c[0] = n01.c0.dot(v2.a);
  p.numerator.c[1] = n01.c0.dot(v2.b) + n01.c1.dot(v2.a);
  p.numerator.c[2] = n01.c1.dot(v2.b) + n01.c2.dot(v2.a);
  p.numerator.c[3] = n01.c2.dot(v2.b);
  const PointMotion e1{m.v[1].a - m.v[0].a, m.v[1].b - m.v[0].b};
  const PointMotion e2{m.v[2].a - m.v[0].a, m.v[2].b - m.v[0].b};
  p.normal = edge_normal(e1, e2);
  return p;
}
[[nodiscard]] inline DepthPolynomials depth_polynomials(const TriangleMotion& m, double x,
                                                        double y) {
  const DepthParts parts = depth_parts(m);
  return DepthPolynomials{parts.numerator, parts.normal.along(x, y)};
}

/// Camera-space depth of the ray d = (x, y, 1) on the plane of (p0, p1, p2), exactly as the
/// Embree backend reports it: det(p0, p1, p2) / ((p1 - p0) x (p2 - p0)) . d, in double.
/// plane_depth split into the triangle's part, computed once, and each ray's part: the same
/// operations on the same values, so bit-identical to plane_depth for every ray.
struct TrianglePlane {
  TrianglePlane(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2)
      : numerator(p0.dot(p1.cross(p2))), normal((p1 - p0).cross(p2 - p0)) {}
  [[nodiscard]] double depth(double x, double y) const {
    return numerator / normal.dot(Eigen::Vector3d(x, y, 1.0));
  }
  double numerator;
  Eigen::Vector3d normal;
};
[[nodiscard]] inline double plane_depth(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                        const Eigen::Vector3d& p2, double x, double y) {
  return TrianglePlane(p0, p1, p2).depth(x, y);
}

}  // namespace kinray
