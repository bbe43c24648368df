#pragma once
// The sign rule for coverage (docs/design.md, "The sign rule"): the ray d (not the line) pierces
// the triangle iff E_01(d), E_12(d), E_20(d) all have the sign of O and O != 0. It holds for
// triangles in front of, straddling and behind the eye, so nothing is ever clipped.
//
// Signs are always taken "just after now" (sign_after), in initialisation, events and audit
// alike, so that the structure and its certificates agree exactly and an event never re-fires at
// the instant it was processed. An edge function that vanishes identically on a segment (a ray
// lying exactly in the plane of the eye and an edge for a whole segment) is decided by a symbolic
// perturbation of the ray, d -> d + (eps, eps^2, 0) (EdgeNormal::perturbed): its sign is that of
// n_x, or of n_y when n_x vanishes too (n = p x q). The two triangles sharing an edge have opposite
// normals, so exactly one of them claims such a ray, whatever their winding: no crack and no
// double cover. Along a row the perturbed signs are those of the linear function E at x + eps, so
// they still form one step (a zero column joins the side of sign n_x) and the boundary slots stay
// valid. The same perturbed sign decides coverage, slots, certificates and the audit. O must be
// strictly non-zero, so an edge-on or degenerate triangle covers nothing.
#include <array>
#include <cmath>

#include "kinetic/core/polynomial.h"
#include "kinetic/core/root_finding.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {

/// sign_after(f, s) with 0 (the zero polynomial) read as +1: the perturbed sign of a vertex's side
/// of a row plane, and of an edge function whose edge passes through the eye all segment long.
[[nodiscard]] inline int sign_plus(const Polynomial& f, double s) {
  return sign_after(f, s) >= 0 ? 1 : -1;
}

/// sign_plus(f, s) for f = c0 + c1 s + c2 s^2 stored with degree 2, without building it: the
/// operations of Horner's rule and of sign_after_root's Taylor shift ((c1 + s c2) + s c2, then
/// c2), written out.
[[nodiscard]] inline int quadratic_sign_plus(double c0, double c1, double c2, double s) {
  const double v = (c2 * s + c1) * s + c0;
  if (v > 0) return 1;
  if (v < 0) return -1;
  const double d = (c1 + s * c2) + s * c2;
  if (d != 0) return d < 0 ? -1 : 1;  // NaN: sign_after_root's 0, read as +1
  return c2 < 0 ? -1 : 1;
}

/// sign_plus(n.perturbed(x, y), s) for the normal n times `k` (+1, or -1 for the reversed
/// normal, an exact negation of each coefficient): the first of E(d), n_x, n_y that is not the
/// zero polynomial, its sign read by quadratic_sign_plus, without building the polynomials.
[[nodiscard]] inline int perturbed_sign(const EdgeNormal& n, double k, double x, double y,
                                        double s) {
  const Eigen::Vector3d a = k * n.c0, b = k * n.c1, c = k * n.c2;
  const double e0 = a.x() * x + a.y() * y + a.z(), e1 = b.x() * x + b.y() * y + b.z(),
               e2 = c.x() * x + c.y() * y + c.z();
  if (e0 != 0 || e1 != 0 || e2 != 0) return quadratic_sign_plus(e0, e1, e2, s);
  if (a.x() != 0 || b.x() != 0 || c.x() != 0) return quadratic_sign_plus(a.x(), b.x(), c.x(), s);
  return quadratic_sign_plus(a.y(), b.y(), c.y(), s);
}

/// The sign of edge function n . d along the perturbed ray of (x, y, 1) just after s where
/// Horner's value there is an exact 0 (rare, but thousands per frame on a flat cloth): out of
/// line, so that the callers' fast paths keep small frames.
[[gnu::noinline]] inline int perturbed_edge_sign(const EdgeNormal& n, double x, double y, double s) {
  return perturbed_sign(n, 1, x, y, s);
}
/// The same for the reversed normal (EdgeNormal::reversed).
[[gnu::noinline]] inline int perturbed_reversed_edge_sign(const EdgeNormal& n, double x, double y,
                                                         double s) {
  return perturbed_sign(n, -1, x, y, s);
}

/// sign_plus(row_side(v, y), s) where Horner's value is not decided (an exact 0 or not a number),
/// out of line like the edge signs' fallbacks: sign_after_root's sign of the linear coefficient,
/// 0 (and a NaN) read as +1.
[[gnu::noinline]] inline int row_side_sign_at_root(const PointMotion& v, double y, double) {
  return v.b.y() - y * v.b.z() < 0 ? -1 : 1;
}

/// sign_plus(row_side(v, y), s): the side of the row plane of y that v is on just after s, +1 on
/// it. Horner's value of row_side's two coefficients written out, the same operations; the
/// polynomial is built only where that value is 0 or not a number (rare). A vertex-row event and
/// a record's rows take a few of these each.
[[nodiscard]] inline int row_side_sign(const PointMotion& v, double y, double s) {
  const double value = (v.b.y() - y * v.b.z()) * s + (v.a.y() - y * v.a.z());
  if (value > 0) return 1;
  if (value < 0) return -1;
  return row_side_sign_at_root(v, y, s);
}

/// sign_plus(z, s) for z the boundary depth of edge pq on the row plane of y, oriented so that
/// it is positive in front of the eye (boundary_depth, negated where q is on the negative side
/// of the plane): +1 in front, -1 behind. The same value as from the polynomials: Horner's value
/// of z from its coefficients written out (the products and differences of operator* and
/// operator-, which add only zeros for the terms they leave out), the polynomials built only
/// where a value is not a finite non-zero (rare). A boundary is located and placed by this sign.
[[nodiscard]] inline int boundary_front_sign(const PointMotion& p, const PointMotion& q, double y,
                                             double s) {
  const double side_q0 = q.a.y() - y * q.a.z(), side_q1 = q.b.y() - y * q.b.z();
  const double side_p0 = p.a.y() - y * p.a.z(), side_p1 = p.b.y() - y * p.b.z();
  const double z0 = p.a.z() * side_q0 - q.a.z() * side_p0;
  const double z1 =
      (p.a.z() * side_q1 + p.b.z() * side_q0) - (q.a.z() * side_p1 + q.b.z() * side_p0);
  const double z2 = p.b.z() * side_q1 - q.b.z() * side_p1;
  const double v = (z2 * s + z1) * s + z0, side = side_q1 * s + side_q0;
  if (!(v != 0 && side != 0 && std::isfinite(v) && std::isfinite(side))) {
    const Polynomial z = boundary_depth(p, q, y);
    return sign_plus(sign_plus(row_side(q, y), s) > 0 ? z : -z, s);
  }
  // -z's Horner value is the exact negation of z's.
  return (v > 0) == (side > 0) ? 1 : -1;
}

/// One edge function n . d along the ray d = (x, y, 1): along(x, y)'s coefficients and Horner's
/// value at s, with the operations of edge_sign (which is built on it). A boundary event
/// computes it once per watched column and hands it on to that column's certificate
/// (FrustumBand::edge_failure_time) and to the coverage test of the column it crossed.
struct EdgeOnRay {
  double x, c0, c1, c2, v;
  // c0, c1, c2 are EdgeNormal::along_coefficients(x, y), written out: built through that array
  // the boundary events cost 0.25% more instructions (wavy-sphere's event protocol).
  EdgeOnRay(const EdgeNormal& n, double x_, double y, double s)
      : x(x_),
        c0(n.c0.x() * x_ + n.c0.y() * y + n.c0.z()),
        c1(n.c1.x() * x_ + n.c1.y() * y + n.c1.z()),
        c2(n.c2.x() * x_ + n.c2.y() * y + n.c2.z()),
        v((c2 * s + c1) * s + c0) {}
  /// edge_sign(n, x, y, s), for the n, y and s it was built from.
  [[nodiscard]] int sign(const EdgeNormal& n, double y, double s) const {
    // Horner's value: when it is not zero it is the sign, and E is not the zero polynomial (no
    // perturbation, no derivative).
    if (v != 0) return v > 0 ? 1 : -1;
    return perturbed_edge_sign(n, x, y, s);
  }
};

/// The sign (+1 or -1) of edge function n . d along the perturbed ray of (x, y, 1) just after s.
[[nodiscard]] inline int edge_sign(const EdgeNormal& n, double x, double y, double s) {
  return EdgeOnRay(n, x, y, s).sign(n, y, s);
}

/// edge_sign(n.reversed(), x, y, s) without building the reversed normal: its along(x, y) and
/// Horner's value are the exact negations of n's, so only an exact 0 needs the reversed normal.
[[nodiscard]] inline int reversed_edge_sign(const EdgeNormal& n, double x, double y, double s) {
  const double v = EdgeOnRay(n, x, y, s).v;
  if (v != 0) return v > 0 ? -1 : 1;
  return perturbed_reversed_edge_sign(n, x, y, s);
}

/// CoverageRule(m, s, orientation_sign).covers_in_row(x, y, a, b) for a single ray, building only
/// the two edge normals it tests (`known`, when given, is edge `known_edge` already built): the
/// same operations on the same values, so the same answer bit for bit.
[[nodiscard]] inline bool covers_in_row(const TriangleMotion& m, double s, int orientation_sign,
                                        double x, double y, int a, int b,
                                        const EdgeNormal* known = nullptr, int known_edge = -1) {
  if (orientation_sign == 0) return false;
  auto sign_of = [&](int e) {
    return e == known_edge ? edge_sign(*known, x, y, s) : edge_sign(m.edge(e), x, y, s);
  };
  return sign_of(a) == orientation_sign && sign_of(b) == orientation_sign;
}

/// The sign rule at one instant for many rays of one triangle: the orientation's sign is taken
/// once, the edge functions per ray.
class CoverageRule {
 public:
  /// The triangle `m` (in its segment's local time) just after local time s.
  CoverageRule(const TriangleMotion& m, double s) : m_s(s) {
    for (int e = 0; e < 3; ++e) m_edges[e] = m.edge(e);
    m_orientation = sign_after(m.orientation(), s);
  }
  /// The same with the sign of O just after s already known (the band keeps it per triangle).
  CoverageRule(const TriangleMotion& m, double s, int orientation_sign)
      : m_orientation(orientation_sign), m_s(s) {
    for (int e = 0; e < 3; ++e) m_edges[e] = m.edge(e);
  }
  /// Sign of O just after s (0 when O vanishes identically).
  [[nodiscard]] int orientation_sign() const { return m_orientation; }
  [[nodiscard]] const EdgeNormal& edge(int e) const { return m_edges[e]; }
  /// Does the (perturbed) ray (x, y, 1) pierce the triangle just after s?
  [[nodiscard]] bool covers(double x, double y) const {
    if (m_orientation == 0) return false;
    for (int e = 0; e < 3; ++e)
      if (edge_sign(m_edges[e], x, y, m_s) != m_orientation) return false;
    return true;
  }
  /// The sign rule restricted to a row plane that edges a and b cross: there the third edge's
  /// sign follows from the other two (the cone from the eye over the row segment is the wedge
  /// between the planes of a and b), so only a and b are tested. This equals covers() except at
  /// degenerate instants (the third edge lying in the row plane, when rounding can make its sign
  /// lag the vertex-row event by an ulp), and depends only on what the row record tracks.
  [[nodiscard]] bool covers_in_row(double x, double y, int a, int b) const {
    return m_orientation != 0 && edge_sign(m_edges[a], x, y, m_s) == m_orientation &&
           edge_sign(m_edges[b], x, y, m_s) == m_orientation;
  }

 private:
  std::array<EdgeNormal, 3> m_edges;
  int m_orientation = 0;
  double m_s = 0;
};

}  // namespace kinray
