// Exact polynomial arithmetic over the rationals and Descartes root isolation in the Bernstein
// basis (Collins and Akritas 1976; Mourrain, Rouillier and Roy 2005 for the Bernstein form).
#include "kinetic/core/rational_polynomial.h"

#include <array>
#include <cmath>
#include <optional>
#include <utility>

#include "kinetic/core/interval_arithmetic.h"

namespace kinray {

void use_default_gmp_allocation() {
  mp_set_memory_functions(nullptr, nullptr, nullptr);  // nullptr: GMP's default for each
}
namespace {

using detail::Interval;

void trim(std::vector<mpq_class>& c) {
  while (!c.empty() && sgn(c.back()) == 0) c.pop_back();
}

/// Quotient and remainder of f / g (g non-zero).
std::pair<RationalPolynomial, RationalPolynomial> divide(const RationalPolynomial& f,
                                                         const RationalPolynomial& g) {
  std::vector<mpq_class> r = f.c;
  const int dg = g.degree();
  std::vector<mpq_class> q(r.size() >= g.c.size() ? r.size() - g.c.size() + 1 : 0);
  while (static_cast<int>(r.size()) - 1 >= dg && !r.empty()) {
    const int shift = static_cast<int>(r.size()) - 1 - dg;
    const mpq_class k = r.back() / g.c.back();
    q[shift] = k;
    for (int i = 0; i <= dg; ++i) r[shift + i] -= k * g.c[i];
    r.pop_back();  // the leading term cancels exactly
    trim(r);
  }
  return {RationalPolynomial(std::move(q)), RationalPolynomial(std::move(r))};
}

RationalPolynomial monic(RationalPolynomial f) {
  if (f.is_zero()) return f;
  const mpq_class lead = f.c.back();
  for (mpq_class& x : f.c) x /= lead;
  return f;
}

/// Bounds that keep interval Horner evaluation far from overflow (so its ends are never NaN):
/// coefficients below 2^300, |t| below 2^32, degree at most 16.
constexpr double kMaxFilterCoefficient = 0x1p300, kMaxFilterTime = 0x1p32;
constexpr int kMaxFilterDegree = 16;

/// f's coefficients as double intervals that contain them (mpq_get_d truncates, off by less
/// than an ulp); nothing when one is too large for the filter.
std::optional<std::vector<Interval>> enclose(const RationalPolynomial& f) {
  if (f.degree() > kMaxFilterDegree) return std::nullopt;
  std::vector<Interval> c;
  c.reserve(f.c.size());
  for (const mpq_class& x : f.c) {
    const double d = x.get_d();
    if (!(std::fabs(d) < kMaxFilterCoefficient)) return std::nullopt;
    c.push_back(Interval::around(d));
  }
  return c;
}

/// Horner's scheme in interval arithmetic: an enclosure of f over t.
Interval horner(const std::vector<Interval>& f, Interval t) {
  Interval value = Interval::point(0);
  for (auto it = f.rbegin(); it != f.rend(); ++it) value = value * t + *it;
  return value;
}

/// Bernstein coefficients of f on [lo, hi] in interval arithmetic, each scaled by a positive
/// constant: b_k = sum_{i <= k} C(k, i) / C(n, i) q_i (bernstein_coefficients) times n! / k! is
/// sum_{i <= k} (n - i)! / (k - i)! q_i, whose weights are integers, exact in doubles. Their
/// signs are the Bernstein coefficients' signs; f lies in their hull on [lo, hi].
std::vector<Interval> scaled_interval_bernstein(std::vector<Interval> q, double lo, double hi) {
  const int n = int(q.size()) - 1;
  const Interval a = Interval::point(lo);
  for (int i = 0; i < n; ++i)
    for (int j = n - 1; j >= i; --j) q[size_t(j)] = q[size_t(j)] + a * q[size_t(j) + 1];
  const Interval h = Interval::point(hi) - a;
  Interval power = Interval::point(1);
  for (int i = 0; i <= n; ++i, power = power * h) q[size_t(i)] = q[size_t(i)] * power;
  std::vector<Interval> out(size_t(n) + 1, Interval::point(0));
  for (int k = 0; k <= n; ++k)
    for (int i = 0; i <= k; ++i) {
      double weight = 1;  // (n - i)! / (k - i)!, at most 16!: exact
      for (int f = k - i + 1; f <= n - i; ++f) weight *= f;
      out[size_t(k)] = out[size_t(k)] + Interval::point(weight) * q[size_t(i)];
    }
  return out;
}

/// The sign variations of f's Bernstein coefficients on [lo, hi] when double intervals give
/// every one a certain sign (then they are the exact coefficients' signs); -1 when they do not.
int interval_sign_variations(const RationalPolynomial& f, const mpq_class& lo,
                             const mpq_class& hi) {
  const double l = lo.get_d(), h = hi.get_d();
  if (!(l < h) || mpq_class(l) != lo || mpq_class(h) != hi) return -1;
  if (!(std::fabs(l) < kMaxFilterTime && std::fabs(h) < kMaxFilterTime)) return -1;
  const std::optional<std::vector<Interval>> q = enclose(f);
  if (!q) return -1;
  int variations = 0, last = 0;
  for (const Interval& b : scaled_interval_bernstein(*q, l, h)) {
    const int s = b.certain_sign();
    if (s == 0) return -1;
    variations += last != 0 && s != last;
    last = s;
  }
  return variations;
}

/// f certainly has no root in [lo, hi] (f non-zero): its Bernstein coefficients there, in
/// double intervals, all certainly share one sign. False when doubles cannot tell.
bool certainly_no_root(const RationalPolynomial& f, const mpq_class& lo, const mpq_class& hi) {
  return interval_sign_variations(f, lo, hi) == 0;
}

int sign_variations(const std::vector<int>& signs) {
  int variations = 0, last = 0;
  for (const int s : signs) {
    if (s == 0) continue;
    if (last != 0 && s != last) ++variations;
    last = s;
  }
  return variations;
}

/// Roots of p, none multiple in [a, b], in the open (a, b), whose ends are not roots, in order.
void descartes(const RationalPolynomial& p, const mpq_class& a, const mpq_class& b,
               std::vector<IsolatedRoot>& out) {
  int variations = interval_sign_variations(p, a, b);
  if (variations < 0) variations = sign_variations(bernstein_signs(p, a, b));
  if (variations == 0) return;
  if (variations == 1) {
    out.push_back({p, a, b});
    return;
  }
  // Split at a point that is not a root (one of any deg + 1 distinct points is not), so that
  // every interval handed out has non-root ends.
  mpq_class m = (a + b) / 2;
  for (int k = 1; sgn(p(m)) == 0; ++k) m = a + (b - a) * mpq_class(k, p.degree() + 2);
  descartes(p, a, m, out);
  descartes(p, m, b, out);
}

/// The double interval [lo, hi] around x: exact when x is a double.
Interval enclose(const mpq_class& x) {
  const double d = x.get_d();  // truncated towards zero
  if (mpq_class(d) == x) return Interval::point(d);
  return {std::nextafter(d, -INFINITY), std::nextafter(d, INFINITY)};
}

/// The floating-point filter of sign_at: g's sign over the root's interval in outward-rounded
/// double intervals. While that does not decide and the interval's ends are doubles, the
/// interval is halved where the isolating polynomial's sign at the midpoint is certain, and
/// the narrowed ends are written back (each has a certain, non-zero sign, so the root stays
/// isolated), for later calls and the exact path to start from. 0 when doubles cannot decide.
int interval_sign_at(const RationalPolynomial& g, IsolatedRoot& root) {
  const Interval lo0 = enclose(root.lo), hi0 = enclose(root.hi);
  if (!(std::fabs(lo0.lo) < kMaxFilterTime && std::fabs(hi0.hi) < kMaxFilterTime)) return 0;
  const std::optional<std::vector<Interval>> gi = enclose(g);
  if (!gi) return 0;
  int sign = horner(*gi, {lo0.lo, hi0.hi}).certain_sign();
  if (sign != 0 || root.is_rational() || lo0.lo != lo0.hi || hi0.lo != hi0.hi) return sign;
  const std::optional<std::vector<Interval>> pi = enclose(root.poly);
  if (!pi) return 0;
  double lo = lo0.lo, hi = hi0.hi;
  const int sign_lo = horner(*pi, Interval::point(lo)).certain_sign();
  while (sign == 0 && sign_lo != 0) {
    const double mid = 0.5 * (lo + hi);
    if (!(mid > lo && mid < hi)) break;
    const int sign_mid = horner(*pi, Interval::point(mid)).certain_sign();
    if (sign_mid == 0) break;
    (sign_mid == sign_lo ? lo : hi) = mid;
    sign = horner(*gi, {lo, hi}).certain_sign();
  }
  if (lo != lo0.lo) root.lo = lo;
  if (hi != hi0.hi) root.hi = hi;
  return sign;
}

}  // namespace

RationalPolynomial::RationalPolynomial(std::vector<mpq_class> coefficients)
    : c(std::move(coefficients)) {
  trim(c);
}

RationalPolynomial RationalPolynomial::linear(const mpq_class& a, const mpq_class& b) {
  return RationalPolynomial({a, b});
}

mpq_class RationalPolynomial::operator()(const mpq_class& t) const {
  mpq_class value = 0;
  for (auto it = c.rbegin(); it != c.rend(); ++it) value = value * t + *it;
  return value;
}

RationalPolynomial RationalPolynomial::derivative() const {
  std::vector<mpq_class> d;
  for (std::size_t i = 1; i < c.size(); ++i) d.push_back(c[i] * static_cast<long>(i));
  return RationalPolynomial(std::move(d));
}

RationalPolynomial operator+(const RationalPolynomial& f, const RationalPolynomial& g) {
  std::vector<mpq_class> s(std::max(f.c.size(), g.c.size()));
  for (std::size_t i = 0; i < f.c.size(); ++i) s[i] += f.c[i];
  for (std::size_t i = 0; i < g.c.size(); ++i) s[i] += g.c[i];
  return RationalPolynomial(std::move(s));
}

RationalPolynomial operator-(const RationalPolynomial& f, const RationalPolynomial& g) {
  std::vector<mpq_class> s(std::max(f.c.size(), g.c.size()));
  for (std::size_t i = 0; i < f.c.size(); ++i) s[i] += f.c[i];
  for (std::size_t i = 0; i < g.c.size(); ++i) s[i] -= g.c[i];
  return RationalPolynomial(std::move(s));
}

RationalPolynomial operator*(const RationalPolynomial& f, const RationalPolynomial& g) {
  if (f.is_zero() || g.is_zero()) return {};
  std::vector<mpq_class> p(f.c.size() + g.c.size() - 1);
  for (std::size_t i = 0; i < f.c.size(); ++i)
    for (std::size_t j = 0; j < g.c.size(); ++j) p[i + j] += f.c[i] * g.c[j];
  return RationalPolynomial(std::move(p));
}

RationalPolynomial gcd(RationalPolynomial f, RationalPolynomial g) {
  while (!g.is_zero()) {
    RationalPolynomial r = divide(f, g).second;
    f = std::move(g);
    g = monic(std::move(r));  // monic remainders keep the coefficients small
  }
  return monic(std::move(f));
}

RationalPolynomial squarefree_part(const RationalPolynomial& f) {
  if (f.degree() <= 1) return f;
  const RationalPolynomial g = gcd(f, f.derivative());
  return g.degree() <= 0 ? f : divide(f, g).first;
}

int sign(const mpq_class& x) {
  return sgn(x);
}

std::vector<int> bernstein_signs(const RationalPolynomial& f, const mpq_class& a,
                                 const mpq_class& b) {
  const int n = f.degree();
  if (n < 0) return {};
  mpz_class lcm = 1;
  for (const mpq_class& c : f.c) mpz_lcm(lcm.get_mpz_t(), lcm.get_mpz_t(), c.get_den_mpz_t());
  std::vector<mpz_class> c(f.c.size());
  for (std::size_t j = 0; j < c.size(); ++j) c[j] = f.c[j].get_num() * (lcm / f.c[j].get_den());
  const mpq_class h = b - a;
  const mpz_class r = a.get_den() * h.get_den();
  const mpz_class p_term = a.get_num() * h.get_den(), q_term = h.get_num() * a.get_den();
  // g = (((c_n (P + Q s) + c_{n-1} R) (P + Q s) + c_{n-2} R^2) ...)
  std::vector<mpz_class> g(size_t(n) + 1, 0);
  g[0] = c[size_t(n)];
  mpz_class r_power = r;
  for (int j = n - 1, degree = 0; j >= 0; --j, ++degree, r_power *= r) {
    // g (P + Q s): from the top down, so that each g_i is read before it is overwritten
    g[size_t(degree) + 1] = g[size_t(degree)] * q_term;
    for (int i = degree; i >= 1; --i)
      g[size_t(i)] = g[size_t(i)] * p_term + g[size_t(i) - 1] * q_term;
    g[0] = g[0] * p_term + c[size_t(j)] * r_power;
  }
  std::vector<int> signs(size_t(n) + 1);
  mpz_class sum, weight;
  for (int k = 0; k <= n; ++k) {
    sum = 0;
    for (int i = 0; i <= k; ++i) {
      mpz_bin_uiui(weight.get_mpz_t(), (unsigned long)(n - i), (unsigned long)(k - i));
      mpz_addmul(sum.get_mpz_t(), weight.get_mpz_t(), g[size_t(i)].get_mpz_t());
    }
    signs[size_t(k)] = sgn(sum);
  }
  return signs;
}

std::vector<mpq_class> bernstein_coefficients(const RationalPolynomial& f, const mpq_class& a,
                                              const mpq_class& b) {
  std::vector<mpq_class> q = f.c;
  const int n = f.degree();
  if (n < 0) return {};
  // q(s) = f(a + (b - a) s): a Taylor shift by a, then a scaling by b - a.
  for (int i = 0; i < n; ++i)
    for (int j = n - 1; j >= i; --j) q[j] += a * q[j + 1];
  const mpq_class h = b - a;
  mpq_class power = 1;
  for (int i = 0; i <= n; ++i, power *= h) q[i] *= power;
  // b_k = sum_{i <= k} C(k, i) / C(n, i) q_i
  std::vector<mpq_class> binomial_n(n + 1);
  binomial_n[0] = 1;
  for (int i = 1; i <= n; ++i) binomial_n[i] = binomial_n[i - 1] * (n - i + 1) / i;
  std::vector<mpq_class> out(n + 1);
  for (int k = 0; k <= n; ++k) {
    mpq_class binomial_k = 1;  // C(k, i)
    for (int i = 0; i <= k; ++i) {
      out[k] += binomial_k / binomial_n[i] * q[i];
      binomial_k = binomial_k * (k - i) / (i + 1);
    }
  }
  return out;
}

void IsolatedRoot::refine() {
  if (is_rational()) return;
  const mpq_class m = (lo + hi) / 2;
  const int sm = sgn(poly(m));
  if (sm == 0)
    lo = hi = m;
  else if (sgn(poly(lo)) != sm)
    hi = m;
  else
    lo = m;
}

void IsolatedRoot::refine_to(const mpq_class& width) {
  while (!is_rational() && hi - lo > width) refine();
}

std::vector<IsolatedRoot> isolate_roots(const RationalPolynomial& f, const mpq_class& lo,
                                        const mpq_class& hi) {
  std::vector<IsolatedRoot> roots;
  if (lo < hi && certainly_no_root(f, lo, hi)) return roots;
  // f' without a root in [lo, hi]: f's roots there are simple, and f serves as the square-free
  // part on [lo, hi] (all that the isolation, refinement and sign_at's gcd test need of it).
  const bool monotone = lo < hi && f.degree() >= 2 && certainly_no_root(f.derivative(), lo, hi);
  RationalPolynomial p = monotone ? f : squarefree_part(f);
  if (p.degree() <= 0) return roots;
  const bool root_at_lo = sgn(p(lo)) == 0, root_at_hi = lo < hi && sgn(p(hi)) == 0;
  if (root_at_lo) roots.push_back({p, lo, lo});
  if (lo == hi) return roots;
  // Divide out the roots at the ends (simple, as every root of p in [lo, hi]), so that the
  // open interval's roots are isolated by a polynomial that does not vanish at its ends.
  if (root_at_lo) p = divide(p, RationalPolynomial::linear(-lo, 1)).first;
  if (root_at_hi) p = divide(p, RationalPolynomial::linear(-hi, 1)).first;
  if (p.degree() >= 1) descartes(p, lo, hi, roots);
  if (root_at_hi) roots.push_back({p, hi, hi});
  return roots;
}

/// The sign of g at the root, known not to be zero: refining the root until g's Bernstein
/// coefficients on its interval agree in sign.
int sign_apart_from_zero(const RationalPolynomial& g, IsolatedRoot& root) {
  for (;;) {
    bool positive = true, negative = true;
    for (const int x : bernstein_signs(g, root.lo, root.hi)) {
      positive = positive && x > 0;
      negative = negative && x < 0;
    }
    if (positive) return 1;
    if (negative) return -1;
    root.refine();  // g(root) != 0, so the hull shrinks onto one sign
    if (root.is_rational()) return sgn(g(root.lo));
  }
}

int sign_at(const RationalPolynomial& g, IsolatedRoot& root) {
  if (g.is_zero()) return 0;
  if (const int s = interval_sign_at(g, root); s != 0) return s;
  if (root.is_rational()) return sgn(g(root.lo));
  if (root.poly.degree() == 1) {  // the root is rational: pinned, g's sign is one evaluation
    root.lo = root.hi = -root.poly.c[0] / root.poly.c[1];
    return sgn(g(root.lo));
  }
  if (root.poly.degree() == 2) {
    // Rational roots when the discriminant is a square: pinned. Otherwise two irrational
    // conjugates, and g vanishes at one exactly when the quadratic divides it: the remainder,
    // of degree below 2, would otherwise vanish at an irrational number.
    const mpq_class& a = root.poly.c[2];
    const mpq_class& b = root.poly.c[1];
    const mpq_class discriminant = b * b - 4 * a * root.poly.c[0];
    if (sgn(discriminant) >= 0 && mpz_perfect_square_p(discriminant.get_num_mpz_t()) &&
        mpz_perfect_square_p(discriminant.get_den_mpz_t())) {
      mpq_class square_root;
      mpz_sqrt(square_root.get_num_mpz_t(), discriminant.get_num_mpz_t());
      mpz_sqrt(square_root.get_den_mpz_t(), discriminant.get_den_mpz_t());
      const std::array<mpq_class, 2> roots = {(-b - square_root) / (2 * a),
                                              (-b + square_root) / (2 * a)};
      for (const mpq_class& r : roots)
        if (root.lo <= r && r <= root.hi) {
          root.lo = root.hi = r;
          return sgn(g(root.lo));
        }
    } else if (divide(g, root.poly).second.is_zero()) {
      return 0;
    } else {
      return sign_apart_from_zero(g, root);
    }
  }
  // Doubles did not decide even on the narrowed interval: most likely g vanishes there.
  // h = gcd divides poly, so inside [lo, hi] its only possible root is the isolated one,
  // simple; the ends are not roots of poly, hence not of h.
  const RationalPolynomial h = gcd(root.poly, g);
  if (h.degree() >= 1 && sgn(h(root.lo)) != sgn(h(root.hi))) return 0;
  return sign_apart_from_zero(g, root);
}

}  // namespace kinray
