// Exact primitive CCD. A contact needs the four points coplanar, so contact times are roots of
// the cubic det(p1 - p0, p2 - p0, p3 - p0); at such a time the contact is real when a 2-D test
// holds, written as sign conditions on polynomials in t and evaluated exactly at the algebraic
// root (rational_polynomial.h). When the cubic is identically zero the 2-D test alone decides;
// it holds on a closed set whose every component starts and ends at 0, 1 or a root of one of
// its polynomials (elsewhere every sign, hence the test, is locally constant), so testing those
// finitely many times finds every component.
#include "kinetic/collision/exact_ccd.h"

#include <algorithm>
#include <functional>
#include <memory>
#include <utility>

#include "kinetic/core/rational_polynomial.h"

namespace kinray {
namespace {

/// A polynomial with integer coefficients (trailing zeros allowed): the test's polynomials are
/// built in these, from the coordinates scaled to integers (integer_coordinates), because GMP's
/// integer products and sums skip the gcds that every rational one costs; each is converted to
/// a RationalPolynomial once built. The tests are homogeneous in the coordinates, so the scaling
/// keeps every sign and every root.
struct IntegerPolynomial {
  std::vector<mpz_class> c;
};

IntegerPolynomial operator+(const IntegerPolynomial& f, const IntegerPolynomial& g) {
  IntegerPolynomial s{std::vector<mpz_class>(std::max(f.c.size(), g.c.size()))};
  for (std::size_t i = 0; i < f.c.size(); ++i) s.c[i] += f.c[i];
  for (std::size_t i = 0; i < g.c.size(); ++i) s.c[i] += g.c[i];
  return s;
}

IntegerPolynomial operator-(const IntegerPolynomial& f, const IntegerPolynomial& g) {
  IntegerPolynomial s{std::vector<mpz_class>(std::max(f.c.size(), g.c.size()))};
  for (std::size_t i = 0; i < f.c.size(); ++i) s.c[i] += f.c[i];
  for (std::size_t i = 0; i < g.c.size(); ++i) s.c[i] -= g.c[i];
  return s;
}

IntegerPolynomial operator*(const IntegerPolynomial& f, const IntegerPolynomial& g) {
  if (f.c.empty() || g.c.empty()) return {};
  IntegerPolynomial p{std::vector<mpz_class>(f.c.size() + g.c.size() - 1)};
  for (std::size_t i = 0; i < f.c.size(); ++i)
    for (std::size_t j = 0; j < g.c.size(); ++j)
      mpz_addmul(p.c[i + j].get_mpz_t(), f.c[i].get_mpz_t(), g.c[j].get_mpz_t());
  return p;
}

RationalPolynomial rational(const IntegerPolynomial& f) {
  return RationalPolynomial(std::vector<mpq_class>(f.c.begin(), f.c.end()));
}

using IntegerVec = std::array<IntegerPolynomial, 3>;
using PolyVec = std::array<RationalPolynomial, 3>;

PolyVec rational(const IntegerVec& v) {
  return {rational(v[0]), rational(v[1]), rational(v[2])};
}

IntegerVec operator-(const IntegerVec& a, const IntegerVec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

IntegerVec cross(const IntegerVec& a, const IntegerVec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

IntegerPolynomial dot(const IntegerVec& a, const IntegerVec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The four points' motions with every coordinate multiplied by the least common multiple of
/// the coordinates' denominators (a power of two for doubles), and that multiple.
std::pair<std::array<IntegerVec, 4>, mpz_class> integer_motions(const RationalMotion& motion) {
  mpz_class scale = 1;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k)
      for (const mpq_class* x : {&motion.start[i][k], &motion.end[i][k]})
        mpz_lcm(scale.get_mpz_t(), scale.get_mpz_t(), x->get_den_mpz_t());
  std::array<IntegerVec, 4> p;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      const auto integer = [&](const mpq_class& x) -> mpz_class {
        return x.get_num() * (scale / x.get_den());
      };
      const mpz_class start = integer(motion.start[i][k]);
      p[i][k].c = {start, integer(motion.end[i][k]) - start};
    }
  return {std::move(p), std::move(scale)};
}

/// Signs of polynomials at one candidate time.
using SignOracle = std::function<int(const RationalPolynomial&)>;

bool is_zero_at(const PolyVec& v, const SignOracle& sign_of) {
  return sign_of(v[0]) == 0 && sign_of(v[1]) == 0 && sign_of(v[2]) == 0;
}

/// Point p on the closed segment [a, b] (a point when a == b).
struct PointOnSegment {
  PolyVec w, r, w_cross_r;            // w = b - a, r = p - a
  RationalPolynomial from_a, from_b;  // (p - a).(b - a), (p - b).(a - b)

  PointOnSegment(const IntegerVec& p, const IntegerVec& a, const IntegerVec& b) {
    const IntegerVec wi = b - a, ri = p - a;
    w = rational(wi);
    r = rational(ri);
    w_cross_r = rational(cross(wi, ri));
    from_a = rational(dot(ri, wi));
    from_b = rational(dot(p - b, a - b));
  }

  [[nodiscard]] bool holds(const SignOracle& sign_of) const {
    if (is_zero_at(w, sign_of)) return is_zero_at(r, sign_of);
    return is_zero_at(w_cross_r, sign_of) && sign_of(from_a) >= 0 && sign_of(from_b) >= 0;
  }
  void collect(std::vector<const RationalPolynomial*>& out) const {
    for (const PolyVec* v : {&w, &r, &w_cross_r})
      for (const RationalPolynomial& p : *v) out.push_back(&p);
    out.push_back(&from_a);
    out.push_back(&from_b);
  }
};

/// The 2-D test of a pair known to be coplanar at the candidate time, and its polynomials.
class ContactCondition {
 public:
  virtual ~ContactCondition() = default;
  [[nodiscard]] virtual bool holds(const SignOracle& sign_of) const = 0;
  virtual void collect(std::vector<const RationalPolynomial*>& out) const = 0;
};

/// Vertex v in the closed triangle (f0, f1, f2): barycentric signs when the triangle has an
/// area, else v on one of its (possibly degenerate) edges.
class VertexInTriangle final : public ContactCondition {
 public:
  explicit VertexInTriangle(const std::array<IntegerVec, 4>& p) : m_points(p) {
    const IntegerVec normal = cross(p[2] - p[1], p[3] - p[1]);
    m_normal = rational(normal);
    for (int i = 0; i < 3; ++i) {
      const IntegerVec& a = p[1 + i];
      const IntegerVec& b = p[1 + (i + 1) % 3];
      m_barycentric[i] = rational(dot(normal, cross(b - a, p[0] - a)));
    }
  }
  [[nodiscard]] bool holds(const SignOracle& sign_of) const override {
    if (!is_zero_at(m_normal, sign_of))
      return std::ranges::all_of(m_barycentric,
                                 [&](const RationalPolynomial& s) { return sign_of(s) >= 0; });
    return std::ranges::any_of(edges(), [&](const PointOnSegment& e) { return e.holds(sign_of); });
  }
  void collect(std::vector<const RationalPolynomial*>& out) const override {
    for (const RationalPolynomial& p : m_normal) out.push_back(&p);
    for (const RationalPolynomial& p : m_barycentric) out.push_back(&p);
    for (const PointOnSegment& e : edges()) e.collect(out);
  }

 private:
  /// Only a triangle without area needs them: built on first use.
  const std::vector<PointOnSegment>& edges() const {
    if (m_edges.empty())
      for (int i = 0; i < 3; ++i)
        m_edges.emplace_back(m_points[0], m_points[1 + i], m_points[1 + (i + 1) % 3]);
    return m_edges;
  }

  std::array<IntegerVec, 4> m_points;
  PolyVec m_normal;
  std::array<RationalPolynomial, 3> m_barycentric;
  mutable std::vector<PointOnSegment> m_edges;
};

/// Closed edges (a0, a1) and (b0, b1) meet: the crossing parameters of the two lines when they
/// are not parallel, else an end point of one lies on the other.
class EdgesMeet final : public ContactCondition {
 public:
  explicit EdgesMeet(const std::array<IntegerVec, 4>& p) : m_points(p) {
    const IntegerVec normal = cross(p[1] - p[0], p[3] - p[2]);
    const IntegerVec d = p[2] - p[0];
    const IntegerPolynomial norm2 = dot(normal, normal);
    // a0 + s (a1 - a0) = b0 + u (b1 - b0) with s = m_s / m_norm2, u = m_u / m_norm2
    const IntegerPolynomial s = dot(cross(d, p[3] - p[2]), normal);
    const IntegerPolynomial u = dot(cross(d, p[1] - p[0]), normal);
    m_normal = rational(normal);
    m_norm2 = rational(norm2);
    m_s = rational(s);
    m_u = rational(u);
    m_s_rest = rational(norm2 - s);
    m_u_rest = rational(norm2 - u);
  }
  [[nodiscard]] bool holds(const SignOracle& sign_of) const override {
    if (!is_zero_at(m_normal, sign_of))
      return sign_of(m_s) >= 0 && sign_of(m_s_rest) >= 0 && sign_of(m_u) >= 0 &&
             sign_of(m_u_rest) >= 0;
    return std::ranges::any_of(ends(), [&](const PointOnSegment& e) { return e.holds(sign_of); });
  }
  void collect(std::vector<const RationalPolynomial*>& out) const override {
    for (const RationalPolynomial& p : m_normal) out.push_back(&p);
    for (const RationalPolynomial* p : {&m_norm2, &m_s, &m_u, &m_s_rest, &m_u_rest})
      out.push_back(p);
    for (const PointOnSegment& e : ends()) e.collect(out);
  }

 private:
  /// Only parallel edges need them: built on first use.
  const std::vector<PointOnSegment>& ends() const {
    if (m_ends.empty()) {
      const std::array<IntegerVec, 4>& p = m_points;
      m_ends = {PointOnSegment(p[0], p[2], p[3]), PointOnSegment(p[1], p[2], p[3]),
                PointOnSegment(p[2], p[0], p[1]), PointOnSegment(p[3], p[0], p[1])};
    }
    return m_ends;
  }

  std::array<IntegerVec, 4> m_points;
  PolyVec m_normal;
  RationalPolynomial m_norm2, m_s, m_u, m_s_rest, m_u_rest;
  mutable std::vector<PointOnSegment> m_ends;
};

/// floor(x / kContactTimeEarliness) (x >= 0)
mpz_class grid_floor(const mpq_class& x) {
  mpz_class k;
  const mpq_class scaled = x / mpq_class(kContactTimeEarliness);
  mpz_fdiv_q(k.get_mpz_t(), scaled.get_num_mpz_t(), scaled.get_den_mpz_t());
  return k;
}

/// The root rounded down to the grid of kContactTimeEarliness, by bisection over the grid
/// points between the ends of its isolating interval (the answer depends on the root alone).
double on_grid(const IsolatedRoot& root) {
  const mpq_class e = kContactTimeEarliness;
  mpz_class a = grid_floor(root.lo);
  if (!root.is_rational()) {
    mpz_class b = grid_floor(root.hi) + 1;  // a e <= lo < t* < hi < b e
    const int sign_lo = sgn(root.poly(root.lo));
    while (b - a > 1) {
      const mpz_class m = (a + b) / 2;  // non-negative: truncation is floor
      const mpq_class g = mpq_class(m) * e;
      if (g <= root.lo) {
        a = m;
      } else if (g >= root.hi) {
        b = m;
      } else {
        const int s = sgn(root.poly(g));
        if (s == 0) return g.get_d();  // a grid point, exactly a double
        (s == sign_lo ? a : b) = m;
      }
    }
  }
  return mpq_class(mpq_class(a) * e).get_d();  // k e with k <= 2^48: exactly a double
}

/// The signs of the test's polynomials at one root, each decided once: the test at the root and
/// on both sides of it asks for the same polynomials (sign_at refines the root in place).
class SignsAtRoot {
 public:
  explicit SignsAtRoot(IsolatedRoot& root) : m_root(root) {}

  int at(const RationalPolynomial& g) {
    for (const auto& [known, sign] : m_known)
      if (known == &g) return sign;
    const int sign = sign_at(g, m_root);
    m_known.emplace_back(&g, sign);
    return sign;
  }

  /// The sign of g on a small open interval beside the root (side -1: before it, 1: after
  /// it), where no polynomial changes sign: that of its first derivative not vanishing at the
  /// root, g(t* + h) having the sign of g^(k)(t*) h^k; 0 for the zero polynomial.
  int beside(const RationalPolynomial& g, int side) {
    if (const int s = at(g); s != 0 || g.is_zero()) return s;
    RationalPolynomial d = g.derivative();
    for (int k = 1; !d.is_zero(); ++k, d = d.derivative())
      if (const int s = sign_at(d, m_root); s != 0) return side < 0 && k % 2 == 1 ? -s : s;
    return 0;
  }

  void known(const RationalPolynomial& g, int sign) { m_known.emplace_back(&g, sign); }
  [[nodiscard]] IsolatedRoot& root() { return m_root; }

 private:
  IsolatedRoot& m_root;
  std::vector<std::pair<const RationalPolynomial*, int>> m_known;
};

/// In coplanar motion the pair may touch over whole intervals of time; true when the root lies
/// strictly inside one, the test holding just before and just after it. Such a time is where
/// some other polynomial of the test changes sign, and which polynomials the test has depends on
/// the order of the pair's points (on which triangle pair met it): only the intervals' ends are
/// the pair's own.
bool inside_contact_interval(const ContactCondition& condition, SignsAtRoot& signs) {
  const IsolatedRoot& root = signs.root();
  if (root.is_rational() && (sgn(root.lo) == 0 || root.lo == 1)) return false;
  for (int side : {-1, 1}) {
    const SignOracle beside = [&signs, side](const RationalPolynomial& g) {
      return signs.beside(g, side);
    };
    if (!condition.holds(beside)) return false;
  }
  return true;
}

IntegerPolynomial coplanarity_of(const std::array<IntegerVec, 4>& p) {
  return dot(cross(p[1] - p[0], p[2] - p[0]), p[3] - p[0]);
}

}  // namespace

RationalMotion to_rational(const PrimitiveMotion& motion) {
  RationalMotion m;
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 3; ++k) {
      m.start[i][k] = motion.start[i][k];
      m.end[i][k] = motion.end[i][k];
    }
  return m;
}

RationalPolynomial coplanarity_polynomial(const RationalMotion& motion) {
  const auto [p, scale] = integer_motions(motion);
  RationalPolynomial cubic = rational(coplanarity_of(p));
  const mpq_class volume_scale = mpq_class(scale * scale * scale);  // undoes the scaling
  for (mpq_class& x : cubic.c) x /= volume_scale;
  return cubic;
}

std::vector<double> exact_contact_times(ContactType type, const RationalMotion& motion,
                                        LocalWindow window) {
  const std::array<IntegerVec, 4> p = integer_motions(motion).first;
  const RationalPolynomial coplanarity = rational(coplanarity_of(p));
  std::unique_ptr<const ContactCondition> owned;
  if (type == ContactType::vertex_face)
    owned = std::make_unique<VertexInTriangle>(p);
  else
    owned = std::make_unique<EdgesMeet>(p);
  const ContactCondition& condition = *owned;

  // The candidates of [0, 1] that lie in the window: its ends count only where they are 0 or 1.
  const mpq_class zero = 0, one = 1, lo = window.lo, hi = window.hi;
  std::vector<IsolatedRoot> candidates;
  std::vector<const RationalPolynomial*> sources;  // the polynomial a candidate is a root of
  if (!coplanarity.is_zero()) {
    candidates = isolate_roots(coplanarity, lo, hi);
  } else {
    if (lo == zero) candidates.push_back({RationalPolynomial::linear(0, 1), zero, zero});
    if (hi == one) candidates.push_back({RationalPolynomial::linear(-1, 1), one, one});
    sources.assign(candidates.size(), nullptr);  // 0 and 1
    std::vector<const RationalPolynomial*> polynomials;
    condition.collect(polynomials);
    for (const RationalPolynomial* q : polynomials)
      if (q->degree() >= 1)
        for (IsolatedRoot& r : isolate_roots(*q, lo, hi)) {
          candidates.push_back(std::move(r));
          sources.push_back(q);
        }
  }

  std::vector<double> times;
  sources.resize(candidates.size());  // the cubic's roots: none of the test's polynomials
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    IsolatedRoot& root = candidates[i];
    SignsAtRoot signs(root);
    if (sources[i]) signs.known(*sources[i], 0);  // no gcd needed to find it zero there
    const SignOracle sign_of = [&signs](const RationalPolynomial& g) { return signs.at(g); };
    if (!condition.holds(sign_of)) continue;
    if (coplanarity.is_zero() && inside_contact_interval(condition, signs)) continue;
    times.push_back(on_grid(root));
  }
  std::ranges::sort(times);
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

}  // namespace kinray
