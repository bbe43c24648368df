#pragma once
// Per-pixel depth order (docs/design.md, "Depth order per pixel"). Along the centre
// ray d of a pixel the depth of triangle A is z_A = N_A / D_A with N_A = det(v0, v1, v2) (cubic)
// and D_A = (e1 x e2) . d (quadratic), so "A before B" holds while
//     sign(D_A D_B) (N_B D_A - N_A D_B) > 0,
// a degree-5 certificate. While both cover the pixel D has the sign of O = N (the sign rule), so
// sign(D_A D_B) changes only where O_A or O_B does. At such an orientation event a triangle keeps
// covering the pixel only if the ray lies in its plane at that instant: then N and D vanish
// together, z stays finite and N_B D_A - N_A D_B has a root that is no change of order. Taken
// with a fixed sign(D_A D_B), that root would swap the pair (and, computed apart from the
// orientation event's root, an ulp before or after it, no recomputation at the event can stop
// it). So each such common root r of N_A and D_A (or of N_B and D_B) in the certificate's window
// is divided out: f = sigma (N_B D_A - N_A D_B) / (s - r), sigma = sign of D_A D_B / (s - r) just
// after now, which is constant across r. The certificate is exactly antisymmetric
// in (A, B), its origin is the later of the two segment starts and it ends at the earlier of the
// two next flightplan updates, as the kinetic sorts of kinetic_sort.h require; exact ties
// (identical triangles) give the zero polynomial and are broken by triangle id there. Most pairs
// are proved apart for the rest of the segment first (depth_order_apart) and get the constant
// certificate of their order; pairs the rounded polynomial cannot decide carry their exact form
// (exact_certificate.h) and, while the filter vouches for them, wait for a recheck.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "kinetic/core/root_finding.h"
#include "kinetic/grid/band_motion.h"
#include "kinetic/grid/fold_certificate.h"
#include "kinetic/grid/grid_scene.h"
#include "kinetic/motion/triangle_motion.h"
#include "kinetic/sort/kinetic_sort.h"

namespace kinray {

namespace detail {

/// The real simple roots of a polynomial of degree <= 2 (none for a double root).
struct QuadraticRoots {
  std::array<double, 2> r{};
  int n = 0;
  [[nodiscard]] const double* begin() const { return r.data(); }
  [[nodiscard]] const double* end() const { return r.data() + n; }
};
[[nodiscard]] inline QuadraticRoots quadratic_roots(const Polynomial& p) {
  QuadraticRoots out;
  const double c0 = p.c[0], c1 = p.c[1], c2 = p.degree >= 2 ? p.c[2] : 0.0;
  if (c2 == 0) {
    if (c1 != 0) out.r[size_t(out.n++)] = -c0 / c1;
    return out;
  }
  const double disc = c1 * c1 - 4 * c2 * c0;
  if (!(disc > 0)) return out;
  const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
  out.r[size_t(out.n++)] = q / c2;
  if (q != 0) out.r[size_t(out.n++)] = c0 / q;
  return out;
}

/// Does f vanish at r, up to the rounding of r and of f's evaluation: |f(r)| within `relative`
/// of the magnitude of its terms there?
[[nodiscard]] inline bool vanishes_at(const Polynomial& f, double r, double relative = 1e-9) {
  double value = 0, scale = 0;
  for (int i = f.degree; i >= 0; --i) {
    value = value * r + f.c[size_t(i)];
    scale = scale * std::abs(r) + std::abs(f.c[size_t(i)]);
  }
  return std::abs(value) <= relative * scale;
}

/// f / (s - r) by synthetic division, the remainder (f(r), zero up to rounding) dropped.
[[nodiscard]] inline Polynomial divide_root(const Polynomial& f, double r) {
  const int n = f.effective_degree();
  Polynomial q;
  q.degree = std::max(n - 1, 0);
  double carry = 0;
  for (int i = n; i >= 1; --i) {
    carry = f.c[size_t(i)] + carry * r;
    q.c[size_t(i - 1)] = carry;
  }
  return q;
}

/// Bounds on the exact values of the polynomial c (double coefficients, degree kN <= 3) for s
/// in [a, a + w], a >= 0, w > 0: the hull of its Bernstein coefficients there, widened by a bound
/// on their rounding. The error count is root_finding's Bernstein conversion's (the Taylor shift
/// to a, the powers of w, the conversion: (8 kN + 16) u, with a factor two to spare) times the
/// sum of the shifted magnitudes, which is sum |c_k| (a + w)^k.
struct ValueRange {
  double lo, hi;
};
template <int kN>
[[nodiscard]] inline ValueRange polynomial_range(const double* c, double a, double w) {
  constexpr double kGamma = 2 * (8 * kN + 16) * 0x1p-53;
  std::array<double, kN + 1> g;
  for (int k = 0; k <= kN; ++k) g[size_t(k)] = c[k];
  for (int i = 0; i < kN; ++i)
    for (int k = kN - 1; k >= i; --k) g[size_t(k)] += a * g[size_t(k + 1)];
  const double reach = a + w;
  double magnitude = std::abs(c[kN]);
  for (int k = kN - 1; k >= 0; --k) magnitude = magnitude * reach + std::abs(c[k]);
  const double error = kGamma * magnitude;
  double lo, hi;
  if constexpr (kN == 3) {
    const double g1 = g[1] * w, g2 = g[2] * (w * w), g3 = g[3] * (w * w * w);
    constexpr double kThird = 1.0 / 3;
    const double b1 = g[0] + g1 * kThird, b2 = g[0] + (2 * g1 + g2) * kThird;
    const double b3 = ((g[0] + g1) + g2) + g3;
    lo = std::min(std::min(g[0], b1), std::min(b2, b3));
    hi = std::max(std::max(g[0], b1), std::max(b2, b3));
  } else {
    static_assert(kN == 2);
    const double g1 = g[1] * w, g2 = g[2] * (w * w);
    const double b1 = g[0] + 0.5 * g1, b2 = (g[0] + g1) + g2;
    lo = std::min(std::min(g[0], b1), b2);
    hi = std::max(std::max(g[0], b1), b2);
  }
  lo -= error + std::abs(lo) * 0x1p-50;  // the subtraction's own rounding
  hi += error + std::abs(hi) * 0x1p-50;
  return {lo, hi};
}

/// Is z = N / D on the side `side` (+1: beyond, -1: before) of the depth Z at every instant of
/// local [s0, s0 + w]? D must keep one sign there, and sign(D) (N - Z D), a cubic without the
/// dependency of N on D that an interval quotient N / D would suffer, the sign `side`. The
/// coefficients N_k - Z D_k round (at most 3 u (|N_k| + |Z D_k|) each, counted over the window
/// as polynomial_range counts magnitudes).
[[nodiscard]] inline bool depth_beyond(const DepthCoefficients& p, double z, double s0, double w,
                                       int side) {
  const ValueRange d = polynomial_range<2>(p.d.data(), s0, w);
  const int sign_d = d.lo > 0 ? 1 : (d.hi < 0 ? -1 : 0);
  if (sign_d == 0) return false;
  std::array<double, 4> c;
  const double reach = s0 + w;
  double rounding = 0;
  for (int k = 3; k >= 0; --k) {
    // D has no cubic term: Z times its zero (a signed zero, as when D was a Polynomial).
    const double zd = k < 3 ? z * p.d[size_t(k)] : z * 0.0;
    c[size_t(k)] = p.n[size_t(k)] - zd;
    rounding = rounding * reach + (std::abs(p.n[size_t(k)]) + std::abs(zd));
  }
  const ValueRange r = polynomial_range<3>(c.data(), s0, w);
  const double extra = 4 * 0x1p-53 * rounding;
  return side * sign_d > 0 ? r.lo - extra > 0 : r.hi + extra < 0;
}

/// The window depth_order_apart proves over, from local s0 to at least s1, and its limits.
[[nodiscard]] inline bool apart_window(double s0, double s1) {
  return s0 >= 0 && s0 < s1 && s1 < 0x1p20;
}
[[nodiscard]] inline double apart_width(double s0, double s1) {
  return (s1 - s0) * (1 + 0x1p-50);  // at least s1 - s0
}

/// +1 when z_A < z_B at every instant of local [s0, s1], -1 when z_A > z_B there, 0 when the
/// bounds cannot tell: a depth Z between the two at s0 separates them throughout
/// (depth_beyond). Where it tells, the certificate sign(D_A D_B) (N_B D_A - N_A D_B) =
/// |D_A D_B| (z_B - z_A) has that sign throughout, and no common root of N and D lies inside
/// to be divided out (D keeps its sign). Z is a float where one lies strictly between the two
/// depths (the sorted list keeps it as the certificate's separator, `separator` here; NaN when
/// not apart or Z is not a float).
[[nodiscard]] inline int depth_order_apart(const DepthCoefficients& a, const DepthCoefficients& b,
                                           double s0, double s1, float* separator = nullptr) {
  if (separator != nullptr) *separator = std::numeric_limits<float>::quiet_NaN();
  if (!apart_window(s0, s1)) return 0;
  const double za = a.numerator(s0) / a.denominator(s0), zb = b.numerator(s0) / b.denominator(s0);
  if (!(std::isfinite(za) && std::isfinite(zb)) || za == zb) return 0;
  // Any depth works: the tests below are the proof. The midpoint, rounded to a float when that
  // stays strictly between (symmetric in a and b, as the certificate's antisymmetry needs).
  const double mid = 0.5 * za + 0.5 * zb;
  const double rounded = double(float(mid));
  const bool storable = std::min(za, zb) < rounded && rounded < std::max(za, zb);
  const double z = storable ? rounded : mid;
  const double w = apart_width(s0, s1);
  const int order = za < zb ? 1 : -1;
  if (!(depth_beyond(a, z, s0, w, -order) && depth_beyond(b, z, s0, w, order))) return 0;
  if (separator != nullptr && storable) *separator = float(z);
  return order;
}

/// The same for N and D as Polynomials: 0 unless their degrees are at most 3 and 2.
[[nodiscard]] inline int depth_order_apart(const DepthPolynomials& a, const DepthPolynomials& b,
                                           double s0, double s1) {
  if (a.numerator.degree > 3 || a.denominator.degree > 2 || b.numerator.degree > 3 ||
      b.denominator.degree > 2)
    return 0;
  auto coefficients = [](const DepthPolynomials& p) {
    DepthCoefficients c;
    for (size_t k = 0; k < 4; ++k) c.n[k] = p.numerator.c[k];
    for (size_t k = 0; k < 3; ++k) c.d[k] = p.denominator.c[k];
    return c;
  };
  return depth_order_apart(coefficients(a), coefficients(b), s0, s1);
}

}  // namespace detail

/// The depth keys of one pixel: ids are global triangle ids (kinetic_sort.h's Keys concept).
class PixelDepthKeys {
 public:
  PixelDepthKeys(const BandMotion* source, int column, int row)
      : m_source(source), m_column(column), m_row(row) {}

  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double now) const {
    OrderCertificate c = window_of(a, b);
    // A fold's certificate is built for the lower id first and negated for the other order, so
    // that it is exactly antisymmetric.
    const uint32_t first = std::min(a, b), second = std::max(a, b);
    if (const std::optional<SharedEdge> edge = shared_edge_of(a, b)) {
      c = fold_certificate(first, second, *edge, now, c);
      if (a > b) c.f = -c.f;
      return c;
    }
    const DepthCoefficients ca = m_source->depth_coefficients(a, m_column, m_row, c.origin);
    const DepthCoefficients cb = m_source->depth_coefficients(b, m_column, m_row, c.origin);
    const double s = now - c.origin;
    // Most pairs of a pixel stay apart in depth for the rest of the segment: the certificate is
    // then the constant of their order, without products, envelopes or roots.
    if (const int apart = detail::depth_order_apart(ca, cb, s, c.end - c.origin, &c.separator)) {
      c.f = Polynomial(double(apart));
      return c;
    }
    const DepthPolynomials pa = ca.polynomials(), pb = cb.polynomials();
    Polynomial f = pb.numerator * pa.denominator - pa.numerator * pb.denominator;
    Polynomial da = pa.denominator, db = pb.denominator;
    // The common roots, in one order for (a, b) and (b, a), so that f stays exactly antisymmetric.
    std::array<double, 4> roots;
    int n = 0;
    for (const DepthPolynomials* p : {&pa, &pb})
      for (double r : detail::quadratic_roots(p->denominator))
        if (r >= 0 && r <= c.end - c.origin && detail::vanishes_at(p->numerator, r)) roots[size_t(n++)] = r;
    for (int k = 1; k < n; ++k)  // insertion sort of at most four
      for (int j = k; j > 0 && roots[size_t(j)] < roots[size_t(j - 1)]; --j) std::swap(roots[size_t(j)], roots[size_t(j - 1)]);
    for (int k = 0; k < n; ++k) {
      f = detail::divide_root(f, roots[size_t(k)]);
      // Only one of the two denominators has this root (or both do, the same root twice).
      Polynomial& d = std::abs(da(roots[size_t(k)])) <= std::abs(db(roots[size_t(k)])) ? da : db;
      if (d.effective_degree() > 0) d = detail::divide_root(d, roots[size_t(k)]);
    }
    const int sigma = sign_after(da, s) * sign_after(db, s);
    if (sigma == 0) return c;  // D vanishes only for a triangle that covers nothing: by id
    c.f = sigma < 0 ? -f : f;
    // Near a cluster of roots (both triangles nearly edge-on with the ray nearly in both planes)
    // the two products cancel below their rounding: decide on the exact difference there.
    if (n == 0) {
      const Polynomial& na = pa.numerator;
      const Polynomial& nb = pb.numerator;
      if (!decided_despite(c.f, product_difference_error(nb, da, na, db), s, c.end - c.origin,
                           &c.vouched))
        c.exact = exact_product_difference(nb, da, na, db, sigma);
    }
    return c;
  }

  /// The certificate of (kept, to) from the separator of (kept, from)'s (kinetic_sort.h's
  /// SeparatorKeys): `to` takes `from`'s place across their shared edge, so at `from`'s depth now
  /// and on `from`'s side of the separator, where it mostly stays. `kept`'s side was proved for
  /// the window of (kept, from)'s certificate; when (kept, to)'s is the same (from and to move on
  /// one segment) only `to`'s side is left to prove, by depth_order_apart's test. std::nullopt
  /// when it does not hold or a pair sharing an edge takes its fold certificate.
  [[nodiscard]] std::optional<OrderCertificate> order_certificate_beside(
      uint32_t kept, uint32_t from, uint32_t to, double now, float separator, int side) const {
    const MeshSegment& sf = m_source->segment_of(from);
    const MeshSegment& st = m_source->segment_of(to);
    if (st.origin != sf.origin || st.end != sf.end) return std::nullopt;
    OrderCertificate c = window_of(kept, to);  // (kept, from)'s window, as order_certificate's
    const double s0 = now - c.origin, s1 = c.end - c.origin;
    if (!detail::apart_window(s0, s1) || shared_edge_of(kept, to)) return std::nullopt;
    const DepthCoefficients ct = m_source->depth_coefficients(to, m_column, m_row, c.origin);
    if (!detail::depth_beyond(ct, separator, s0, detail::apart_width(s0, s1), side))
      return std::nullopt;
    c.f = Polynomial(double(side));
    c.separator = separator;
    return c;
  }

  /// Two triangles of one mesh sharing an edge (a seam's two sides too, welded by GridScene;
  /// fold_certificate.h): sign(D_b) kappa times the volume of their four vertices.
  [[nodiscard]] OrderCertificate fold_certificate(uint32_t a, uint32_t b, const SharedEdge& edge,
                                                  double now, OrderCertificate c) const {
    const GridScene& scene = m_source->scene();
    // One mesh, so one segment: the vertices' motions are in the certificate's local time.
    const DepthPolynomials& pb = m_source->depth(b, m_column, m_row, c.origin);
    const int sign_b = sign_after(pb.denominator, now - c.origin);
    if (sign_b == 0) return c;  // D vanishes only for a triangle that covers nothing: by id
    const auto& va = scene.triangle_vertices(a);
    const auto& vb = scene.triangle_vertices(b);
    const Polynomial volume = fold_volume(m_source->vertex(va[size_t(edge.first)]),
                                          m_source->vertex(va[size_t((edge.first + 1) % 3)]),
                                          m_source->vertex(va[size_t((edge.first + 2) % 3)]),
                                          m_source->vertex(vb[size_t(edge.b_other)]));
    c.f = sign_b * edge.kappa > 0 ? volume : -volume;
    return c;
  }

  /// Two triangles sharing an edge have one depth where the pixel's ray meets that edge (their
  /// planes meet along it), and there their fold certificate orders them while their coverage
  /// events, a few ulps away, are still pending: tied when the edge function along the ray is
  /// within its rounding of zero at t (the audit).
  [[nodiscard]] bool tied(uint32_t a, uint32_t b, double t) const {
    const GridScene& scene = m_source->scene();
    const auto& va = scene.triangle_vertices(a);
    const std::optional<SharedEdge> edge = shared_edge(va, scene.triangle_vertices(b));
    if (!edge) return false;
    const EdgeNormal n = edge_normal(m_source->vertex(va[size_t(edge->first)]),
                                     m_source->vertex(va[size_t((edge->first + 1) % 3)]));
    return detail::vanishes_at(n.along(scene.column_x(m_column), scene.row_y(m_row)),
                               t - m_source->segment_of(a).origin, 0x1p-40);
  }

  /// Camera-space depth of triangle a along this pixel's ray at t (for audits); at an instant
  /// where the ray lies in the triangle's plane (N = D = 0) the limit N' / D'.
  [[nodiscard]] double value(uint32_t a, double t) const {
    const MeshSegment& sa = m_source->segment_of(a);
    const DepthPolynomials& p = m_source->depth(a, m_column, m_row, sa.origin);
    const double s = t - sa.origin;
    const double n = p.numerator(s), d = p.denominator(s);
    if (d == 0 && n == 0) return p.numerator.derivative()(s) / p.denominator.derivative()(s);
    return n / d;
  }

  [[nodiscard]] int column() const { return m_column; }
  [[nodiscard]] int row() const { return m_row; }

 private:
  /// A certificate of (a, b) with no polynomial yet: from the later of their segments' starts to
  /// the earlier of their ends.
  [[nodiscard]] OrderCertificate window_of(uint32_t a, uint32_t b) const {
    const MeshSegment& sa = m_source->segment_of(a);
    const MeshSegment& sb = m_source->segment_of(b);
    OrderCertificate c;
    c.origin = std::max(sa.origin, sb.origin);
    c.end = std::min(sa.end, sb.end);
    return c;
  }
  /// The edge two triangles share (fold_certificate.h), looked up in one order for (a, b) and
  /// (b, a): the lower id's triangle first.
  [[nodiscard]] std::optional<SharedEdge> shared_edge_of(uint32_t a, uint32_t b) const {
    const GridScene& scene = m_source->scene();
    return shared_edge(scene.triangle_vertices(std::min(a, b)),
                       scene.triangle_vertices(std::max(a, b)));
  }

  const BandMotion* m_source;
  int32_t m_column, m_row;
};

static_assert(SeparatorKeys<PixelDepthKeys>);

}  // namespace kinray
