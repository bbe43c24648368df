// Interval enclosures over a time interval T of the coplanarity cubic, its derivative and the
// 2-D test's polynomials. A contact at t needs the cubic to vanish at t and, the triangle
// having an area (or the edges not being parallel), every polynomial below to be >= 0 at t;
// each is a dot product with the normal, so one certainly negative proves the normal non-zero
// and the degenerate branch of the rational test (exact_ccd.cpp) out of reach, and all of them
// certainly positive prove the contact. A cubic certainly monotone on T with certain, opposite
// signs at T's ends has exactly one root, inside T.
#include "kinetic/collision/interval_ccd.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "kinetic/collision/exact_ccd.h"
#include "kinetic/core/interval_arithmetic.h"

namespace kinray {
namespace {

using detail::Interval;
using detail::IntervalVec;

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

/// All relative motions of the four points, computed once per pair.
class PairMotion {
 public:
  PairMotion(ContactType type, const PrimitiveMotion& m) : m_type(type), m_motion(m) {
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
  /// d/dt det(X, Y, Z) = det(X', Y, Z) + det(X, Y', Z) + det(X, Y, Z')
  [[nodiscard]] Interval cubic_derivative(Interval t) const {
    const IntervalVec x = at(0, 1, t), y = at(0, 2, t), z = at(0, 3, t);
    return det(m_rel[0][1]->b, y, z) + det(x, m_rel[0][2]->b, z) + det(x, y, m_rel[0][3]->b);
  }

  /// Signs of the 2-D test's polynomials over t: -1 when one is certainly negative (no
  /// contact), 1 when all are certainly positive (contact wherever coplanar), else 0.
  [[nodiscard]] int condition(Interval t) const {
    Interval q[4];
    int count = 0;
    if (m_type == ContactType::vertex_face) {
      // vertex p0, triangle (p1, p2, p3): barycentric numerators n . ((b - a) x (p0 - a))
      const IntervalVec n = cross(at(1, 2, t), at(1, 3, t));
      constexpr int corner[3][2] = {{1, 2}, {2, 3}, {3, 1}};
      for (const auto& [a, b] : corner) q[count++] = dot(n, cross(at(a, b, t), at(a, 0, t)));
    } else {
      // edges (p0, p1), (p2, p3), n = (p1 - p0) x (p3 - p2): s |n|^2, (1 - s) |n|^2, u |n|^2,
      // (1 - u) |n|^2, each one triple product with n so that no enclosure is subtracted
      const IntervalVec ea = at(0, 1, t), eb = at(2, 3, t), d = at(0, 2, t);
      const IntervalVec n = cross(ea, eb);
      q[count++] = dot(cross(d, eb), n);
      q[count++] = dot(cross(at(2, 1, t), eb), n);
      q[count++] = dot(cross(d, ea), n);
      q[count++] = dot(cross(ea, at(0, 3, t)), n);
    }
    bool all_positive = true;
    for (int i = 0; i < count; ++i) {
      if (q[i].certainly_negative()) return -1;
      all_positive = all_positive && q[i].certainly_positive();
    }
    return all_positive ? 1 : 0;
  }

 private:
  ContactType m_type;
  const PrimitiveMotion& m_motion;
  std::optional<RelativeMotion> m_rel[4][4];
};

/// Bisection work per pair: a pair that needs more goes to the rational decision.
constexpr int kMaxDepth = 10;
constexpr int kMaxIntervals = 96;

/// Splits the window until every piece is free of contact or holds exactly one certified contact
/// (appended to `contacts`, in time order); false when the budget runs out first.
bool classify(const PairMotion& pair, Interval t, int depth, int& budget,
              std::vector<Interval>& contacts) {
  if (--budget < 0) return false;
  if (pair.cubic(t).certainly_nonzero()) return true;
  const int condition = pair.condition(t);
  if (condition < 0) return true;
  if (condition == 0 && pair.separated(t)) return true;
  if (condition > 0 && pair.cubic_derivative(t).certainly_nonzero()) {
    const int at_lo = pair.cubic(Interval::point(t.lo)).certain_sign();
    const int at_hi = pair.cubic(Interval::point(t.hi)).certain_sign();
    if (at_lo != 0 && at_hi != 0) {
      if (at_lo != at_hi) contacts.push_back(t);
      return true;
    }
  }
  if (depth == kMaxDepth) return false;
  const double mid = 0.5 * (t.lo + t.hi);  // inside [lo, hi] however it rounds
  return classify(pair, {t.lo, mid}, depth + 1, budget, contacts) &&
         classify(pair, {mid, t.hi}, depth + 1, budget, contacts);
}

/// The coplanarity cubic's monomial coefficients in plain doubles, constant term first: no
/// bound on their error, only a guide to where the root lies.
std::array<double, 4> approximate_cubic(const PrimitiveMotion& m) {
  Eigen::Vector3d a[3], b[3];
  for (int q = 1; q <= 3; ++q) {
    a[q - 1] = m.start[q] - m.start[0];
    b[q - 1] = (m.end[q] - m.end[0]) - a[q - 1];
  }
  const auto det = [](const Eigen::Vector3d& x, const Eigen::Vector3d& y,
                      const Eigen::Vector3d& z) { return x.dot(y.cross(z)); };
  return {
      det(a[0], a[1], a[2]), det(b[0], a[1], a[2]) + det(a[0], b[1], a[2]) + det(a[0], a[1], b[2]),
      det(a[0], b[1], b[2]) + det(b[0], a[1], b[2]) + det(b[0], b[1], a[2]), det(b[0], b[1], b[2])};
}

/// Newton's method kept inside the bracket (t.lo, t.hi), whose ends' signs are known: a guess
/// of the root, usually within a grid cell or two of it, never a certificate.
double guess_root(const std::array<double, 4>& c, Interval t, int sign_lo) {
  double lo = t.lo, hi = t.hi, x = 0.5 * (lo + hi);
  for (int iteration = 0; iteration < 60 && hi - lo > kContactTimeEarliness; ++iteration) {
    const double value = ((c[3] * x + c[2]) * x + c[1]) * x + c[0];
    const double slope = (3 * c[3] * x + 2 * c[2]) * x + c[1];
    if (value == 0) return x;
    ((value > 0) == (sign_lo > 0) ? lo : hi) = x;
    const double step = value / slope;
    const double next = x - step;
    x = next > lo && next < hi ? next : 0.5 * (lo + hi);
    if (std::fabs(step) < 0.25 * kContactTimeEarliness) break;
  }
  return x;
}

/// floor(t* / e) e for the only root t* of the cubic inside (t.lo, t.hi): a bisection over the
/// grid points k e, each signed in doubles when its enclosure allows, else in long doubles, else
/// exactly. It starts at the grid points around a Newton guess of the root, which usually
/// bracket it at once: two signs instead of some forty.
double grid_floor_of_root(const PairMotion& pair, const PrimitiveMotion& motion, Interval t,
                          IntervalCcdCounters& counters) {
  constexpr double e = kContactTimeEarliness;
  const int sign_lo = pair.cubic(Interval::point(t.lo)).certain_sign();
  double a = std::floor(t.lo / e), b = std::ceil(t.hi / e);  // a e <= lo < t* < hi <= b e
  std::optional<RationalPolynomial> cubic;
  // Which side of the root grid point m e lies on: -1 below, 1 above, 0 exactly on it.
  const auto side = [&](double m) {
    const double g = m * e;
    if (g <= t.lo) return -1;
    if (g >= t.hi) return 1;
    int s = pair.cubic(Interval::point(g)).certain_sign();
    if (s == 0) s = detail::extended_cubic_sign(motion, g);
    if (s == 0) {
      ++counters.exact_signs;
      if (!cubic) cubic = coplanarity_polynomial(to_rational(motion));
      s = sign((*cubic)(mpq_class(g)));
      if (s == 0) return 0;
    }
    return s == sign_lo ? -1 : 1;
  };
  // from the guess's cell, steps doubling towards the root until it is bracketed; then bisection
  double m = std::floor(guess_root(approximate_cubic(motion), t, sign_lo) / e), step = 1;
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

/// Products of up to five coordinate differences stay far from overflow below this.
constexpr double kMaxCoordinate = 0x1p150;

}  // namespace

// Long double has 64-bit significands on x86-64: next to a root, where the double enclosure
// holds zero, these 11 more bits usually still decide. The bound, in the manner of
// Shewchuk's orient3d: each difference d = a + g b (a = s_q - s_0, b = e_q - e_0 - a, g in
// [0, 1]), after its five roundings, is off by at most u (2 |a| + |e_q - e_0| + 2 |b| + |d|)
// (to first order; 3 u times the sum of the four covers it); a product
// x' y' z' of perturbed factors is off by at most ex By Bz + Bx ey Bz + Bx By ez (B bounding
// both the exact and the computed factor); the cross and dot products add at most 6 roundings
// of each term. Products of three differences of doubles cannot underflow in long double.
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

std::optional<std::vector<double>> interval_contact_times(ContactType type,
                                                          const PrimitiveMotion& motion,
                                                          IntervalCcdCounters& counters,
                                                          LocalWindow window) {
  for (int i = 0; i < 4; ++i)
    if (motion.start[i].cwiseAbs().maxCoeff() >= kMaxCoordinate ||
        motion.end[i].cwiseAbs().maxCoeff() >= kMaxCoordinate)
      return std::nullopt;
  const PairMotion pair(type, motion);
  std::vector<Interval> contacts;
  int budget = kMaxIntervals;
  if (!classify(pair, {window.lo, window.hi}, 0, budget, contacts)) return std::nullopt;
  std::vector<double> times;
  for (const Interval& t : contacts) times.push_back(grid_floor_of_root(pair, motion, t, counters));
  times.erase(std::unique(times.begin(), times.end()), times.end());  // two roots, one grid cell
  if (times.empty())
    ++counters.rejections;
  else
    ++counters.contacts;
  return times;
}

}  // namespace kinray
