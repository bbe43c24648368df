// The floating-point decision of primitive CCD over the window, bisected into pieces. A contact
// at t needs the coplanarity cubic to vanish at t and, the triangle having an area (or the
// edges not being parallel), every polynomial of the 2-D test to be >= 0 at t; each is a dot
// product with the normal, so one certainly negative proves the normal non-zero and the
// degenerate branch of the rational test (exact_ccd.cpp) out of reach, and all of them
// certainly positive prove the contact. A cubic certainly monotone on a piece with certain,
// opposite signs at its ends has exactly one root, inside it. The polynomials are enclosed in
// Bernstein form on the window once per pair (doubles from the positions at the window's ends,
// with a forward error bound), and halved with the pieces (bernstein_bound.h).
#include "kinetic/collision/interval_ccd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <tuple>

#include "kinetic/collision/axis_plane.h"
#include "kinetic/collision/bernstein_bound.h"
#include "kinetic/collision/exact_ccd.h"
#include "kinetic/core/interval_arithmetic.h"

namespace kinray {
namespace {

using detail::BernsteinBound;
using detail::Interval;
using detail::IntervalVec;
using detail::Tracked;
using detail::TrackedVec;

/// The relative motion q(t) - p(t) = A + t B of two linearly moving points: A, and B = dA/dt.
/// Written in this form an enclosure does not pay twice for the motion both points share.
struct RelativeMotion {
  IntervalVec a, b;

  RelativeMotion(const PrimitiveMotion& m, int p, int q) {
    Interval* ak[3] = {&a.x, &a.y, &a.z};
    Interval* bk[3] = {&b.x, &b.y, &b.z};
    for (int k = 0; k < 3; ++k) {
      *ak[k] = Interval::around(m.start[q][k] - m.start[p][k]);
      *bk[k] = Interval::around(m.end[q][k] - m.end[p][k]) - *ak[k];
    }
  }
  [[nodiscard]] IntervalVec over(Interval t) const {
    return {a.x + t * b.x, a.y + t * b.y, a.z + t * b.z};
  }
};

/// The relative position q - p at local time t in doubles, with the magnitude |a| + |b| of its
/// motion a + t b: off by at most 6 u of it (five roundings from the coordinates).
detail::TrackedVec tracked_at(const PrimitiveMotion& m, int p, int q, double t) {
  detail::Tracked out[3];
  for (int k = 0; k < 3; ++k) {
    const double a = m.start[q][k] - m.start[p][k];
    const double b = (m.end[q][k] - m.end[p][k]) - a;
    out[k] = {a + t * b, std::fabs(a) + std::fabs(b)};
  }
  return {out[0], out[1], out[2]};
}

/// Error bound of the Bernstein coefficients below, relative to their magnitudes: their inputs
/// are off by 6 u each (three or four per term: 24 u), and no path from them takes more than 10
/// roundings; twice that.
constexpr double kRelativeError = 68 * std::numeric_limits<double>::epsilon() / 2;

/// All relative motions of the four points, computed once per pair.
class PairMotion {
 public:
  PairMotion(ContactType type, const PrimitiveMotion& m, std::optional<AxisPlaneTriple> plane)
      : m_type(type), m_motion(m), m_plane(plane) {
    for (int p = 0; p < 4; ++p)
      for (int q = 0; q < 4; ++q)
        if (p != q) m_rel[p][q].emplace(m, p, q);
  }

  [[nodiscard]] IntervalVec at(int p, int q, Interval t) const { return m_rel[p][q]->over(t); }

  /// A plane strictly between the two primitives all over t: no contact there, whatever the
  /// cubic does. Catches what the signs cannot: coplanar motion and parallel edges apart. The
  /// candidate normals come from the geometry at t's middle; any fixed normal is sound, the
  /// enclosures of the gaps decide.
  [[nodiscard]] bool separated(Interval t) const {
    const int first = m_type == ContactType::vertex_face ? 1 : 2;
    const std::array<Eigen::Vector3d, 4> p = m_motion.at(0.5 * (t.lo + t.hi));
    Eigen::Vector3d ca = Eigen::Vector3d::Zero(), cb = Eigen::Vector3d::Zero();
    for (int i = 0; i < 4; ++i) (i < first ? ca : cb) += p[i];
    const Eigen::Vector3d w = cb / (4 - first) - ca / first;
    Eigen::Vector3d axes[3] = {w, w, w};
    if (m_type == ContactType::edge_edge) {
      // perpendicular to one edge: parallel edges side by side
      for (int e = 0; e < 2; ++e) {
        const Eigen::Vector3d d = p[2 * e + 1] - p[2 * e];
        if (d.squaredNorm() > 0) axes[1 + e] = w - (w.dot(d) / d.squaredNorm()) * d;
      }
    }
    for (const Eigen::Vector3d& axis : axes) {
      if (!axis.allFinite() || axis.squaredNorm() == 0) continue;
      const IntervalVec n = {Interval::point(axis.x()), Interval::point(axis.y()),
                             Interval::point(axis.z())};
      bool apart = true;
      for (int i = 0; i < first && apart; ++i)
        for (int j = first; j < 4 && apart; ++j) apart = dot(n, at(i, j, t)).certainly_positive();
      if (apart) return true;
    }
    return false;
  }

  [[nodiscard]] Interval cubic(Interval t) const {
    return det(at(0, 1, t), at(0, 2, t), at(0, 3, t));
  }
  /// The polynomials of conditions_on, each up to its positive factor, enclosed over t (a cell
  /// around a root, too narrow for the Bernstein bounds to halve down to); returns how many.
  int conditions_over(Interval t, std::array<Interval, 4>& out) const {
    if (m_plane) {
      const auto [s0, s1] = m_plane->segment;
      out[0] = dot(at(s0, m_plane->point, t), at(s0, s1, t));
      out[1] = dot(at(s1, m_plane->point, t), at(s1, s0, t));
      return 2;
    }
    if (m_type == ContactType::vertex_face) {
      const IntervalVec n = cross(at(1, 2, t), at(1, 3, t));
      constexpr int corner[3][2] = {{1, 2}, {2, 3}, {3, 1}};
      for (int i = 0; i < 3; ++i)
        out[size_t(i)] = dot(n, cross(at(corner[i][0], corner[i][1], t), at(corner[i][0], 0, t)));
      return 3;
    }
    const IntervalVec ea = at(0, 1, t), eb = at(2, 3, t), d = at(0, 2, t);
    const IntervalVec n = cross(ea, eb);
    out[0] = dot(cross(d, eb), n);
    out[1] = dot(cross(at(2, 1, t), eb), n);
    out[2] = dot(cross(d, ea), n);
    out[3] = dot(cross(ea, at(0, 3, t)), n);
    return 4;
  }
  /// The 2-D test's polynomials on [lo, hi] in Bernstein form (each times a positive factor);
  /// returns how many (3 for vertex-face, 4 for edge-edge, 2 for three points on an axis plane).
  int conditions_on(double lo, double hi, std::array<BernsteinBound<4>, 4>& out) const {
    using detail::Tracked;
    using detail::TrackedVec;
    // a linear vector's ends; a quadratic one's Bernstein coefficients (times 2: (u x v)_1 is
    // the mean of the two cross terms)
    using Linear = std::array<TrackedVec, 2>;
    using Quadratic = std::array<TrackedVec, 3>;
    const auto linear = [&](int p, int q) -> Linear {
      return {tracked_at(m_motion, p, q, lo), tracked_at(m_motion, p, q, hi)};
    };
    const auto crossed = [](const Linear& u, const Linear& v) -> Quadratic {
      return {2 * cross(u[0], v[0]), cross(u[0], v[1]) + cross(u[1], v[0]), 2 * cross(u[1], v[1])};
    };
    // n . m of two quadratics, times 12: 12 n0m0, 6 (n0m1 + n1m0), 2 (n0m2 + 4 n1m1 + n2m0), ...
    const auto product = [](const Quadratic& n, const Quadratic& m) {
      const auto w = [](double x) { return Tracked{x, x}; };
      const std::array<Tracked, 5> b = {
          w(12) * dot(n[0], m[0]), w(6) * (dot(n[0], m[1]) + dot(n[1], m[0])),
          w(2) * (dot(n[0], m[2]) + w(4) * dot(n[1], m[1]) + dot(n[2], m[0])),
          w(6) * (dot(n[1], m[2]) + dot(n[2], m[1])), w(12) * dot(n[2], m[2])};
      return BernsteinBound<4>::tracking(b, kRelativeError);
    };
    if (m_plane) {
      // The point on the closed segment, given that the three are collinear (at a root of the
      // cubic): (p - s0).(s1 - s0) >= 0 and (p - s1).(s0 - s1) >= 0. Quadratics: 2 u0.v0,
      // u0.v1 + u1.v0, 2 u1.v1, raised to degree 4 (times 6) by positive integer weights.
      const auto along = [&](int from, int to) {
        const Linear u = linear(from, m_plane->point), v = linear(from, to);
        const auto w = [](double x) { return Tracked{x, x}; };
        const Tracked b0 = w(2) * dot(u[0], v[0]), b1 = dot(u[0], v[1]) + dot(u[1], v[0]),
                      b2 = w(2) * dot(u[1], v[1]);
        const std::array<Tracked, 5> b = {w(6) * b0, w(3) * (b0 + b1), b0 + w(4) * b1 + b2,
                                          w(3) * (b1 + b2), w(6) * b2};
        return BernsteinBound<4>::tracking(b, kRelativeError);
      };
      const auto [s0, s1] = m_plane->segment;
      out[0] = along(s0, s1);
      out[1] = along(s1, s0);
      return 2;
    }
    if (m_type == ContactType::vertex_face) {
      // vertex p0, triangle (p1, p2, p3): barycentric numerators n . ((b - a) x (p0 - a))
      const Quadratic n = crossed(linear(1, 2), linear(1, 3));
      constexpr int corner[3][2] = {{1, 2}, {2, 3}, {3, 1}};
      for (int i = 0; i < 3; ++i)
        out[i] = product(n, crossed(linear(corner[i][0], corner[i][1]), linear(corner[i][0], 0)));
      return 3;
    }
    // edges (p0, p1), (p2, p3), n = (p1 - p0) x (p3 - p2): s |n|^2, (1 - s) |n|^2, u |n|^2,
    // (1 - u) |n|^2, each one triple product with n so that no enclosure is subtracted
    const Linear ea = linear(0, 1), eb = linear(2, 3), d = linear(0, 2);
    const Quadratic n = crossed(ea, eb);
    out[0] = product(crossed(d, eb), n);
    out[1] = product(crossed(linear(2, 1), eb), n);
    out[2] = product(crossed(d, ea), n);
    out[3] = product(crossed(ea, linear(0, 3)), n);
    return 4;
  }

 private:
  ContactType m_type;
  const PrimitiveMotion& m_motion;
  /// Three points on an axis plane the fourth never meets: the contact test is theirs.
  std::optional<AxisPlaneTriple> m_plane;
  std::optional<RelativeMotion> m_rel[4][4];
};

/// The time where a piece of the window starts (index k) or ends (k + 1): an exact double at
/// the window's ends and on the dyadic grid of a whole segment, else lo + (hi - lo) k / 2^depth
/// rounded (off by at most 3 u of itself, lo >= 0) and widened by more than that.
Interval piece_boundary(LocalWindow window, double k, int depth) {
  if (k == 0) return Interval::point(window.lo);
  if (k == std::ldexp(1.0, depth)) return Interval::point(window.hi);
  const double at = window.lo + (window.hi - window.lo) * std::ldexp(k, -depth);
  if (window.whole()) return Interval::point(at);
  return {std::max(window.lo, detail::round_down_bound(at)),
          std::min(window.hi, detail::round_up_bound(at))};
}

/// Bisection work per pair: a pair that needs more goes to the rational decision.
constexpr int kMaxDepth = 10;
constexpr int kMaxIntervals = 96;
/// Edges sliding in a plane: where an end of one edge passes near an end of the other, both
/// edges' orientations change sign within a few 1e-5 of each other (cloth folded flat onto
/// itself), which depth 10 cannot separate. The path to them is narrow: two pieces a level.
constexpr int kMaxPlanarDepth = 24;

/// A piece of the window: k-th of 2^depth equal parts, with the polynomials on it.
struct Piece {
  int depth = 0;
  double index = 0;
  BernsteinBound<3> cubic;
  std::array<BernsteinBound<4>, 4> conditions;
};

/// A piece with one simple root of the cubic: an interval of doubles around it (a point for a
/// root exactly at a double), the cubic's sign at its start, and whether the 2-D test still has to
/// be decided at the root (`at_root`): near a segment's end or an edge the test's polynomials are
/// small at the root but change over any piece the bisection reaches, and the root's grid cell
/// (found for its time anyway) decides them.
struct ContactPiece {
  Interval time;
  int sign_lo = 0;
  bool at_root = false;
};

/// The coplanarity cubic's exact sign at a double local time g: its enclosure in doubles, else
/// long double with a static bound, else rationals (the rational cubic built at the first need
/// and kept for the pair's other points).
class CubicSign {
 public:
  CubicSign(const PairMotion& pair, const PrimitiveMotion& motion, IntervalCcdCounters& counters)
      : m_pair(pair), m_motion(motion), m_counters(counters) {}

  int operator()(double g) {
    int s = m_pair.cubic(Interval::point(g)).certain_sign();
    if (s == 0) s = detail::extended_cubic_sign(m_motion, g);
    if (s == 0) {
      ++m_counters.exact_signs;
      if (!m_cubic) m_cubic = coplanarity_polynomial(to_rational(m_motion));
      s = sign((*m_cubic)(mpq_class(g)));
    }
    return s;
  }

 private:
  const PairMotion& m_pair;
  const PrimitiveMotion& m_motion;
  IntervalCcdCounters& m_counters;
  std::optional<RationalPolynomial> m_cubic;
};

/// The bisection of one pair's window.
class Bisection {
 public:
  Bisection(const PairMotion& pair, LocalWindow window, CubicSign& cubic_sign)
      : m_pair(pair), m_window(window), m_cubic_sign(cubic_sign) {}

  /// Splits the window until every piece is free of contact or holds exactly one certified
  /// contact (appended to `contacts`, in time order); false when the budget runs out first.
  bool classify(const BernsteinBound<3>& cubic, std::vector<ContactPiece>& contacts) {
    Piece whole{0, 0, cubic, {}};
    if (cubic.certainly_nonzero()) return true;
    m_conditions = m_pair.conditions_on(m_window.lo, m_window.hi, whole.conditions);
    return classify(whole, contacts);
  }

 private:
  bool classify(const Piece& piece, std::vector<ContactPiece>& contacts) {
    if (--m_budget < 0) return false;
    if (piece.cubic.certainly_nonzero()) return true;
    bool all_positive = true;
    for (int i = 0; i < m_conditions; ++i) {
      if (piece.conditions[i].certainly_negative()) return true;
      all_positive = all_positive && piece.conditions[i].certainly_positive();
    }
    const Interval start = piece_boundary(m_window, piece.index, piece.depth),
                   end = piece_boundary(m_window, piece.index + 1, piece.depth);
    if (!all_positive && m_pair.separated({start.lo, end.hi})) return true;
    if (piece.cubic.certainly_monotone()) {
      // An end coefficient within its slack of zero is the cubic's value there: at an end that
      // is a double, its exact sign. That decides a root within rounding of a segment's end (a
      // key pose in contact or nearly), which no bisection can separate from the end.
      int at_start = piece.cubic.start_sign(), at_end = piece.cubic.end_sign();
      if (at_start == 0 && start.lo == start.hi) at_start = m_cubic_sign(start.lo);
      if (at_end == 0 && end.lo == end.hi) at_end = m_cubic_sign(end.lo);
      if (at_start != 0 && at_start == at_end) return true;  // monotone: no root
      // Exactly zero at an end that is a double (a key pose in contact, or a pair coplanar at a
      // piece boundary) and of certain sign at the other: that end is the piece's only root.
      const bool zero_start = at_start == 0 && start.lo == start.hi;
      const bool zero_end = at_end == 0 && end.lo == end.hi;
      if ((zero_start && at_end != 0) || (zero_end && at_start != 0)) {
        contacts.push_back({Interval::point(zero_start ? start.lo : end.lo), 0, true});
        return true;
      }
      // The root lies strictly inside the piece; where an end is not a double, the few ulps
      // between it and the double outside it must hold no root either.
      const auto clear = [&](Interval sliver, int sign) {
        return sliver.lo == sliver.hi || m_pair.cubic(sliver).certain_sign() == sign;
      };
      if (at_start != 0 && at_end == -at_start && clear(start, at_start) && clear(end, at_end)) {
        contacts.push_back({{start.lo, end.hi}, at_start, !all_positive});
        return true;
      }
    }
    if (piece.depth == kMaxDepth) return false;
    Piece left{piece.depth + 1, 2 * piece.index, {}, {}};
    Piece right{piece.depth + 1, 2 * piece.index + 1, {}, {}};
    std::tie(left.cubic, right.cubic) = piece.cubic.halves();
    for (int i = 0; i < m_conditions; ++i)
      std::tie(left.conditions[i], right.conditions[i]) = piece.conditions[i].halves();
    return classify(left, contacts) && classify(right, contacts);
  }

  const PairMotion& m_pair;
  LocalWindow m_window;
  CubicSign& m_cubic_sign;
  int m_conditions = 0;
  int m_budget = kMaxIntervals;
};

/// Newton's method on a polynomial's Bernstein form on the window (for the cubic, the
/// coefficients the filters computed: the pair's cubic is expanded once), kept inside the
/// bracket (t.lo, t.hi), whose ends' signs are known: a guess of the root, usually within a grid
/// cell or two of it, never a certificate (it only says where the search of certified signs
/// starts). In the window's parameter s, t = lo + s (hi - lo), evaluated by de Casteljau.
template <int N>
double guess_root(const BernsteinBound<N>& f, LocalWindow window, Interval t, int sign_lo) {
  const double width = window.hi - window.lo;
  if (!(width > 0)) return 0.5 * (t.lo + t.hi);
  const auto to_t = [&](double s) { return window.lo + s * width; };
  double lo = (t.lo - window.lo) / width, hi = (t.hi - window.lo) / width, x = 0.5 * (lo + hi);
  const double cell = kContactTimeEarliness / width;
  for (int iteration = 0; iteration < 60 && hi - lo > cell; ++iteration) {
    const double y = 1 - x;
    std::array<double, N + 1> row = f.c;
    for (int level = N; level > 1; --level)
      for (int k = 0; k < level; ++k) row[k] = y * row[k] + x * row[k + 1];
    const double value = y * row[0] + x * row[1], slope = N * (row[1] - row[0]);
    if (value == 0) return to_t(x);
    ((value > 0) == (sign_lo > 0) ? lo : hi) = x;
    const double step = value / slope;
    // converged: x itself, which the bracket's update may just have made one of its ends (a
    // step too small to move x would otherwise fall back to the bracket's middle)
    if (std::fabs(step) < 0.25 * cell) break;
    const double next = x - step;
    x = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return to_t(x);
}

/// floor(t* / e) e for the only root t* of a polynomial inside (t.lo, t.hi), whose sign just
/// after t.lo is sign_lo: a bisection over the grid points k e, each signed exactly by
/// sign_at(g) (certified floating point first, the caller's business). It starts at the grid
/// points around `guess`, which usually bracket the root at once: two signs instead of forty.
template <class SignAt>
double grid_floor_of_root(double guess, Interval t, int sign_lo, SignAt&& sign_at) {
  constexpr double e = kContactTimeEarliness;
  double a = std::floor(t.lo / e), b = std::ceil(t.hi / e);  // a e <= lo < t* < hi <= b e
  // Which side of the root grid point m e lies on: -1 below, 1 above, 0 exactly on it.
  const auto side = [&](double m) {
    const double g = m * e;
    if (g <= t.lo) return -1;
    if (g >= t.hi) return 1;
    const int s = sign_at(g);
    if (s == 0) return 0;
    return s == sign_lo ? -1 : 1;
  };
  // from the guess's cell, steps doubling towards the root until it is bracketed; then bisection
  double m = std::floor(guess / e), step = 1;
  while (b - a > 1 && m > a && m < b) {
    const int s = side(m);
    if (s == 0) return m * e;
    (s < 0 ? a : b) = m;
    m += s < 0 ? step : -step;
    step *= 2;
  }
  while (b - a > 1) {
    const double middle = std::floor(0.5 * (a + b));
    const int s = side(middle);
    if (s == 0) return middle * e;
    (s < 0 ? a : b) = middle;
  }
  return a * e;
}

/// The coplanarity cubic's root on the grid: grid points signed exactly (CubicSign).
double grid_floor_of_cubic_root(const BernsteinBound<3>& cubic_on_window, LocalWindow window,
                                Interval t, int sign_lo, CubicSign& cubic_sign) {
  return grid_floor_of_root(guess_root(cubic_on_window, window, t, sign_lo), t, sign_lo,
                            cubic_sign);
}

/// Edges sliding in one axis plane (all four points on it over the whole segment): they touch
/// where the closed segments meet in the plane, over whole intervals of time, which the
/// rational decision reports by their first and last times (and by 0 and 1 where they touch
/// then). With the four orientations f = (a0 a1 b0, a0 a1 b1, b0 b1 a0, b0 b1 a1) the segments
/// meet exactly when f0 f1 <= 0 and f2 f3 <= 0, unless both orientations of one edge's ends
/// vanish (the edges collinear, or one a point), which is left to the rational decision. The
/// window is bisected until each piece holds at most one root of one orientation, certified
/// simple; the contact set changes only there.
class PlanarEdges {
 public:
  PlanarEdges(const PairMotion& pair, const PrimitiveMotion& motion, int axis, LocalWindow window)
      : m_pair(pair), m_motion(motion), m_axis(axis), m_window(window) {}

  /// The rational decision's times, or nothing when floating point cannot certify them.
  std::optional<std::vector<double>> contact_times() {
    Piece whole;
    for (int i = 0; i < 4; ++i) {
      const auto [p, q, r] = kOrientation[i];
      const std::array<TrackedVec, 2> u = {tracked_at(m_motion, p, q, m_window.lo),
                                           tracked_at(m_motion, p, q, m_window.hi)};
      const std::array<TrackedVec, 2> v = {tracked_at(m_motion, p, r, m_window.lo),
                                           tracked_at(m_motion, p, r, m_window.hi)};
      const auto w = [](double x) { return Tracked{x, x}; };
      const std::array<Tracked, 3> b = {w(2) * component(cross(u[0], v[0])),
                                        component(cross(u[0], v[1])) + component(cross(u[1], v[0])),
                                        w(2) * component(cross(u[1], v[1]))};
      whole.f[i] = BernsteinBound<2>::tracking(b, kRelativeError);
    }
    m_on_window = whole.f;
    if (!classify(whole)) return std::nullopt;
    std::vector<double> times;
    const auto holds = [&](const Signs& s) -> std::optional<bool> {
      if ((s[0] == 0 && s[1] == 0) || (s[2] == 0 && s[3] == 0)) return std::nullopt;
      return s[0] * s[1] <= 0 && s[2] * s[3] <= 0;
    };
    const std::optional<bool> at_start = holds(m_leaves.front().start);
    const std::optional<bool> at_end = holds(m_leaves.back().end);
    if (!at_start || !at_end) return std::nullopt;
    if (m_window.lo == 0 && *at_start) times.push_back(0);
    for (const Leaf& leaf : m_leaves) {
      if (leaf.root < 0) continue;
      Signs at = leaf.start;
      at[size_t(leaf.root)] = 0;
      const std::optional<bool> before = holds(leaf.start), now = holds(at),
                                after = holds(leaf.end);
      if (!before || !now || !after) return std::nullopt;
      if (!*now || (*before && *after)) continue;  // no contact, or inside an interval of them
      const int sign_lo = leaf.start[size_t(leaf.root)];
      const auto sign_at = [&](double g) { return orientation_sign(leaf.root, g); };
      const double guess = guess_root(m_on_window[size_t(leaf.root)], m_window, leaf.time, sign_lo);
      times.push_back(grid_floor_of_root(guess, leaf.time, sign_lo, sign_at));
    }
    if (m_window.hi == 1 && *at_end) times.push_back(1);
    std::ranges::sort(times);
    times.erase(std::unique(times.begin(), times.end()), times.end());
    return times;
  }

 private:
  using Signs = std::array<int, 4>;
  static constexpr int kOrientation[4][3] = {{0, 1, 2}, {0, 1, 3}, {2, 3, 0}, {2, 3, 1}};

  struct Piece {
    int depth = 0;
    double index = 0;
    std::array<BernsteinBound<2>, 4> f;
  };
  /// A piece where every orientation has a certain sign at both ends, at most one changing it.
  struct Leaf {
    Signs start{}, end{};
    int root = -1;  ///< the orientation with a root inside, or -1
    Interval time;
  };

  [[nodiscard]] Tracked component(const TrackedVec& v) const {
    return m_axis == 0 ? v.x : m_axis == 1 ? v.y : v.z;
  }
  [[nodiscard]] Interval orientation(int i, Interval t) const {
    const auto [p, q, r] = kOrientation[i];
    const IntervalVec n = cross(m_pair.at(p, q, t), m_pair.at(p, r, t));
    return m_axis == 0 ? n.x : m_axis == 1 ? n.y : n.z;
  }
  /// The exact sign of orientation i at local time g: intervals, else rationals.
  [[nodiscard]] int orientation_sign(int i, double g) const {
    if (const int s = orientation(i, Interval::point(g)).certain_sign(); s != 0) return s;
    const auto [p, q, r] = kOrientation[i];
    const mpq_class t = g;
    const auto at = [&](int point, int k) -> mpq_class {
      const mpq_class start = m_motion.start[size_t(point)][k];
      return start + t * (mpq_class(m_motion.end[size_t(point)][k]) - start);
    };
    const int x = (m_axis + 1) % 3, y = (m_axis + 2) % 3;
    const mpq_class n = (at(q, x) - at(p, x)) * (at(r, y) - at(p, y)) -
                        (at(q, y) - at(p, y)) * (at(r, x) - at(p, x));
    return sign(n);  // (axis + 1, axis + 2) cyclic: the cross product's component on the axis
  }

  bool classify(const Piece& piece) {
    if (--m_budget < 0) return false;
    Leaf leaf;
    bool certain = true;
    for (int i = 0; i < 4 && certain; ++i) {
      const BernsteinBound<2>& f = piece.f[size_t(i)];
      const int s = f.start_sign(), e = f.end_sign();
      if (f.certainly_positive() || f.certainly_negative() ||
          (s != 0 && s == e && f.certainly_monotone())) {
        leaf.start[size_t(i)] = leaf.end[size_t(i)] = f.c[0] > 0 ? 1 : -1;
      } else if (leaf.root < 0 && s != 0 && e == -s && f.certainly_monotone()) {
        leaf.root = i;
        leaf.start[size_t(i)] = s;
        leaf.end[size_t(i)] = e;
      } else {
        certain = false;
      }
    }
    if (certain) {
      const Interval start = piece_boundary(m_window, piece.index, piece.depth),
                     end = piece_boundary(m_window, piece.index + 1, piece.depth);
      // where an end is not a double, the few ulps between it and the double outside it must
      // hold no root of the rooted orientation either
      const auto clear = [&](Interval sliver, int sign) {
        return sliver.lo == sliver.hi || orientation(leaf.root, sliver).certain_sign() == sign;
      };
      if (leaf.root < 0 || (clear(start, leaf.start[size_t(leaf.root)]) &&
                            clear(end, leaf.end[size_t(leaf.root)]))) {
        leaf.time = {start.lo, end.hi};
        m_leaves.push_back(leaf);
        return true;
      }
    }
    if (piece.depth == kMaxPlanarDepth) return false;
    Piece left{piece.depth + 1, 2 * piece.index, {}};
    Piece right{piece.depth + 1, 2 * piece.index + 1, {}};
    for (size_t i = 0; i < 4; ++i) std::tie(left.f[i], right.f[i]) = piece.f[i].halves();
    return classify(left) && classify(right);
  }

  const PairMotion& m_pair;
  const PrimitiveMotion& m_motion;
  int m_axis = 0;
  LocalWindow m_window;
  int m_budget = kMaxIntervals;
  std::array<BernsteinBound<2>, 4> m_on_window;  ///< the orientations on the whole window
  std::vector<Leaf> m_leaves;                    ///< in time order
};

/// Products of up to five coordinate differences stay far from overflow below this.
constexpr double kMaxCoordinate = 0x1p150;

}  // namespace

// Long double has 64-bit significands on x86-64: next to a root, where the double enclosure
// holds zero, these 11 more bits usually still decide. The bound, in the manner of
// Shewchuk's orient3d: each difference d = a + g b (a = s_q - s_0, b = e_q - e_0 - a, g in
// [0, 1]), after its five roundings, is off by at most u (2 |a| + |e_q - e_0| + 2 |b| + |d|)
// (to first order; 3 u times the sum of the four covers it); a product
// x' y' z' of perturbed factors is off by at most ex By Bz + Bx ey Bz + Bx By ez (B bounding
// both the exact and the computed factor); the six terms' two products and the sum add at most
// 7 roundings of each term. Products of three differences of doubles cannot underflow in long
// double.
int detail::extended_cubic_sign(const PrimitiveMotion& m, double g) {
  using L = long double;
  static_assert(
      std::numeric_limits<L>::max_exponent > 3 * std::numeric_limits<double>::max_exponent &&
          -std::numeric_limits<L>::min_exponent > 3 * 1074,
      "products of three differences of doubles must not overflow or underflow");
  constexpr L u = std::numeric_limits<L>::epsilon() / 2;
  L d[3][3], error[3][3], magnitude[3][3];
  for (int q = 1; q <= 3; ++q)
    for (int k = 0; k < 3; ++k) {
      const L a = L(m.start[q][k]) - L(m.start[0][k]);
      const L moved = L(m.end[q][k]) - L(m.end[0][k]);
      const L b = moved - a;
      d[q - 1][k] = a + L(g) * b;
      error[q - 1][k] =
          3 * u * (std::fabs(a) + std::fabs(moved) + std::fabs(b) + std::fabs(d[q - 1][k]));
      magnitude[q - 1][k] = std::fabs(d[q - 1][k]) + error[q - 1][k];
    }
  // det = sum over the six permutations (i, j, l) of sign d0[i] d1[j] d2[l]
  constexpr int perm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {1, 0, 2}, {2, 1, 0}};
  L value = 0, bound = 0;
  for (int p = 0; p < 6; ++p) {
    const int i = perm[p][0], j = perm[p][1], l = perm[p][2];
    const L term = d[0][i] * d[1][j] * d[2][l];
    value += p < 3 ? term : -term;
    const L bx = magnitude[0][i], by = magnitude[1][j], bz = magnitude[2][l];
    bound += error[0][i] * by * bz + bx * error[1][j] * bz + bx * by * error[2][l] +
             8 * u * bx * by * bz;
  }
  bound *= 1 + 64 * u;  // the bound's own roundings
  return value > bound ? 1 : value < -bound ? -1 : 0;
}

detail::CoplanarityCubic::CoplanarityCubic(const PrimitiveMotion& m, double lo, double hi) {
  // At 0 and 1 a difference is that of the end positions themselves, off by one rounding of its
  // value; elsewhere a + t b, off by 6 u of |a| + |b| (tracked_at).
  const auto difference = [&](int q, double t) -> TrackedVec {
    if (t != 0 && t != 1) return tracked_at(m, 0, q, t);
    const auto& p = t == 0 ? m.start : m.end;
    Tracked out[3];
    for (int k = 0; k < 3; ++k) {
      const double d = p[q][k] - p[0][k];
      out[k] = {d, std::fabs(d)};
    }
    return {out[0], out[1], out[2]};
  };
  // values and magnitudes apart, in plain arrays, which compile to about half the code of the
  // same sums in Tracked pairs
  double x[3][2][3], mag[3][2][3];  // [difference][end][axis]
  for (int q = 0; q < 3; ++q)
    for (int e = 0; e < 2; ++e) {
      const TrackedVec v = difference(q + 1, e == 0 ? lo : hi);
      const Tracked* c[3] = {&v.x, &v.y, &v.z};
      for (int k = 0; k < 3; ++k) {
        x[q][e][k] = c[k]->value;
        mag[q][e][k] = c[k]->magnitude;
      }
    }
  double value[4] = {0, 0, 0, 0}, magnitude[4] = {0, 0, 0, 0};
  for (int j = 0; j < 2; ++j)
    for (int l = 0; l < 2; ++l) {
      const double* y = x[1][j];
      const double* z = x[2][l];
      const double* ym = mag[1][j];
      const double* zm = mag[2][l];
      const double yz[3] = {y[1] * z[2] - y[2] * z[1], y[2] * z[0] - y[0] * z[2],
                            y[0] * z[1] - y[1] * z[0]};
      const double yzm[3] = {ym[1] * zm[2] + ym[2] * zm[1], ym[2] * zm[0] + ym[0] * zm[2],
                             ym[0] * zm[1] + ym[1] * zm[0]};
      for (int i = 0; i < 2; ++i) {
        value[i + j + l] += x[0][i][0] * yz[0] + x[0][i][1] * yz[1] + x[0][i][2] * yz[2];
        magnitude[i + j + l] +=
            mag[0][i][0] * yzm[0] + mag[0][i][1] * yzm[1] + mag[0][i][2] * yzm[2];
      }
    }
  for (int k = 0; k < 4; ++k) b[k] = {value[k], magnitude[k]};
  const Tracked three{3, 3};
  b[0] = three * b[0];
  b[3] = three * b[3];
  // From differences of the end positions, each determinant is off by at most (7 + 56 u) u of
  // its permanent, which is its magnitude here (Shewchuk's orient3d bound), and the sums of
  // three and the products by 3 add three roundings: 16 u leaves room. Elsewhere the inputs
  // are off by 6 u each: kRelativeError.
  const bool ends = (lo == 0 || lo == 1) && (hi == 0 || hi == 1);
  relative = ends ? 16 * std::numeric_limits<double>::epsilon() / 2 : kRelativeError;
}

bool detail::CoplanarityCubic::certainly_nonzero() const {
  int positive = 0, negative = 0;
  for (const Tracked& x : b) {
    // `relative` has room for this product's own rounding
    const double bound = relative * x.magnitude + 256 * std::numeric_limits<double>::denorm_min();
    if (!std::isfinite(bound) || !std::isfinite(x.value)) return false;
    positive += x.value > bound;
    negative += x.value < -bound;
  }
  return positive == 4 || negative == 4;
}

std::optional<std::vector<double>> interval_contact_times(ContactType type,
                                                          const PrimitiveMotion& motion,
                                                          IntervalCcdCounters& counters,
                                                          LocalWindow window) {
  return interval_contact_times(type, motion, counters, window,
                                detail::CoplanarityCubic(motion, window.lo, window.hi).bound());
}

std::optional<std::vector<double>> interval_contact_times(ContactType type,
                                                          const PrimitiveMotion& motion,
                                                          IntervalCcdCounters& counters,
                                                          LocalWindow window,
                                                          const detail::BernsteinBound<3>& cubic) {
  for (int i = 0; i < 4; ++i)
    if (motion.start[i].cwiseAbs().maxCoeff() >= kMaxCoordinate ||
        motion.end[i].cwiseAbs().maxCoeff() >= kMaxCoordinate)
      return std::nullopt;
  std::vector<ContactPiece> contacts;
  const std::optional<AxisPlaneTriple> plane =
      cubic.certainly_nonzero() ? std::nullopt : axis_plane_triple(type, motion);
  if (!cubic.certainly_nonzero() && type == ContactType::edge_edge) {
    if (const std::optional<int> axis = common_axis_plane(motion)) {
      const PairMotion pair(type, motion, std::nullopt);
      std::optional<std::vector<double>> times =
          PlanarEdges(pair, motion, *axis, window).contact_times();
      if (times) ++(times->empty() ? counters.rejections : counters.contacts);
      return times;
    }
  }
  if (!cubic.certainly_nonzero() && !(plane && plane->apart)) {
    const PairMotion pair(type, motion, plane);
    CubicSign cubic_sign(pair, motion, counters);
    if (!Bisection(pair, window, cubic_sign).classify(cubic, contacts)) return std::nullopt;
    std::vector<double> times;
    for (const ContactPiece& c : contacts) {
      // a root at a double is its own cell's: floor(t / e) e is exact (e a power of two)
      const double g = c.time.lo == c.time.hi
                           ? std::floor(c.time.lo / kContactTimeEarliness) * kContactTimeEarliness
                           : grid_floor_of_cubic_root(cubic, window, c.time, c.sign_lo, cubic_sign);
      if (c.at_root) {
        // the root t* lies in [g, g + e) (e a power of two, g a multiple of it in [0, 1]: both
        // ends exact) and in the piece
        const Interval cell = {std::max(g, c.time.lo),
                               std::min(g + kContactTimeEarliness, c.time.hi)};
        std::array<Interval, 4> condition;
        const int n = pair.conditions_over(cell, condition);
        bool all_positive = true, some_negative = false;
        for (int i = 0; i < n; ++i) {
          all_positive = all_positive && condition[size_t(i)].certainly_positive();
          some_negative = some_negative || condition[size_t(i)].certainly_negative();
        }
        if (some_negative) continue;             // the root is no contact
        if (!all_positive) return std::nullopt;  // a contact on the boundary, or rounding
      }
      times.push_back(g);
    }
    times.erase(std::unique(times.begin(), times.end()), times.end());  // two roots, one cell
    if (!times.empty()) {
      ++counters.contacts;
      return times;
    }
  }
  ++counters.rejections;
  return std::vector<double>{};
}

}  // namespace kinray
