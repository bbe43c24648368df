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

/// The sign of the cubic at local time g in long double intervals (64-bit significands on
/// x86-64): near a root, where the double enclosure holds zero, these 11 more bits usually
/// still decide; 0 when they do not either.
int extended_cubic_sign(const PrimitiveMotion& m, double g) {
  using L = long double;
  using LInterval = detail::BasicInterval<L>;
  detail::BasicIntervalVec<L> d[3];
  for (int q = 1; q <= 3; ++q) {
    LInterval* out[3] = {&d[q - 1].x, &d[q - 1].y, &d[q - 1].z};
    for (int k = 0; k < 3; ++k) {
      const LInterval a = LInterval::around(L(m.start[q][k]) - L(m.start[0][k]));
      const LInterval b = LInterval::around(L(m.end[q][k]) - L(m.end[0][k])) - a;
      *out[k] = a + LInterval::point(g) * b;
    }
  }
  return det(d[0], d[1], d[2]).certain_sign();
}

/// floor(t* / e) e for the only root t* of the cubic inside (t.lo, t.hi), by bisection over
/// the grid points k e: each is signed in doubles when its enclosure allows, else exactly.
double grid_floor_of_root(const PairMotion& pair, const PrimitiveMotion& motion, Interval t,
                          IntervalCcdCounters& counters) {
  constexpr double e = kContactTimeEarliness;
  const int sign_lo = pair.cubic(Interval::point(t.lo)).certain_sign();
  double a = std::floor(t.lo / e), b = std::ceil(t.hi / e);  // a e <= lo < t* < hi <= b e
  std::optional<RationalPolynomial> cubic;
  while (b - a > 1) {
    const double m = std::floor(0.5 * (a + b)), g = m * e;
    if (g <= t.lo) {
      a = m;
      continue;
    }
    if (g >= t.hi) {
      b = m;
      continue;
    }
    int s = pair.cubic(Interval::point(g)).certain_sign();
    if (s == 0) s = extended_cubic_sign(motion, g);
    if (s == 0) {
      ++counters.exact_signs;
      if (!cubic) cubic = coplanarity_polynomial(to_rational(motion));
      s = sign((*cubic)(mpq_class(g)));
      if (s == 0) return g;
    }
    (s == sign_lo ? a : b) = m;
  }
  return a * e;
}

/// Products of up to five coordinate differences stay far from overflow below this.
constexpr double kMaxCoordinate = 0x1p150;

}  // namespace

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
