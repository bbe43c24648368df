#include "kinetic/core/exact_certificate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "kinetic/core/certificate_time.h"
#include "kinetic/core/double_steps.h"
#include "kinetic/core/rational_polynomial.h"
#include "kinetic/core/root_finding.h"

namespace kinray {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kU = 0x1p-53;  // unit roundoff

// ---- double-double evaluation with an error bound ----------------------------------------

struct Pair {
  double hi = 0, lo = 0;
};
Pair two_sum(double a, double b) {
  const double s = a + b, bb = s - a;
  return {s, (a - (s - bb)) + (b - bb)};
}
Pair two_product(double a, double b) {
  const double p = a * b;
  return {p, std::fma(a, b, -p)};
}

/// p(t) as hi + lo by compensated Horner (Graillat, Langlois and Louvet 2005), and `bound` >=
/// |hi + lo - p(t)|: gamma_2n^2 times sum |c_k| |t|^k, taken generously.
Pair compensated_horner(const Polynomial& p, double t, double& bound) {
  const int n = p.degree;
  double r = p.c[size_t(n)], c = 0, m = std::abs(r);
  for (int k = n - 1; k >= 0; --k) {
    const Pair pr = two_product(r, t);
    const Pair sm = two_sum(pr.hi, p.c[size_t(k)]);
    r = sm.hi;
    c = c * t + (pr.lo + sm.lo);
    m = m * std::abs(t) + std::abs(p.c[size_t(k)]);
  }
  bound = (8.0 * n * n + 8) * kU * kU * m;
  return {r, c};
}

/// The sign of p1(t) q1(t) - p2(t) q2(t) when double-double arithmetic proves it, else 2.
int filtered_sign(const ExactPolynomial& f, double t) {
  double e[4];
  const Pair a = compensated_horner(f.p1, t, e[0]), b = compensated_horner(f.q1, t, e[1]);
  const Pair c = compensated_horner(f.p2, t, e[2]), d = compensated_horner(f.q2, t, e[3]);
  const Pair x = two_product(a.hi, b.hi), y = two_product(c.hi, d.hi);
  const double rest1 = x.lo + (a.hi * b.lo + a.lo * b.hi);
  const double rest2 = y.lo + (c.hi * d.lo + c.lo * d.hi);
  const Pair head = two_sum(x.hi, -y.hi);
  const double tail = head.lo + (rest1 - rest2);
  const double v = head.hi + tail;
  auto absum = [](Pair p) { return std::abs(p.hi) + std::abs(p.lo); };
  // Errors of the factors carried through the products, the dropped lo * lo terms and the
  // rounding of the tails (each well under 16 u^2 |product| + 8 u |tail|).
  const double bound = e[0] * absum(b) + e[1] * absum(a) + e[0] * e[1] + e[2] * absum(d) +
                       e[3] * absum(c) + e[2] * e[3] +
                       16 * kU * kU * (absum(a) * absum(b) + absum(c) * absum(d)) +
                       8 * kU * (std::abs(tail) + std::abs(v));
  if (!(std::abs(v) > 2 * bound)) return 2;
  return (v > 0 ? 1 : -1) * f.sign;
}

// ---- exact rationals ------------------------------------------------------------------

RationalPolynomial rational(const Polynomial& p) {
  std::vector<mpq_class> c;
  for (int k = 0; k <= p.degree; ++k) c.emplace_back(p.c[size_t(k)]);
  return RationalPolynomial(std::move(c));
}

/// A polynomial of doubles as integers times 2^exponent: every double is an integer times a
/// power of two, and the lowest of the coefficients' powers serves them all. Nothing when the
/// coefficients span too many binades for the integers to be doubles themselves.
struct ScaledIntegers {
  std::vector<mpz_class> c;
  long exponent = 0;
};

std::optional<ScaledIntegers> scaled_integers(const Polynomial& p) {
  int lowest = std::numeric_limits<int>::max();
  for (int k = 0; k <= p.degree; ++k) {
    const double x = p.c[size_t(k)];
    if (x == 0) continue;
    // the last bit of x: 2^(ilogb(x) - 52), or 2^-1074 for a subnormal
    lowest = std::min(lowest, std::max(std::ilogb(x) - 52, -1074));
  }
  ScaledIntegers out;
  if (lowest == std::numeric_limits<int>::max()) {  // the zero polynomial
    out.c.assign(size_t(p.degree) + 1, 0);
    return out;
  }
  out.exponent = lowest;
  for (int k = 0; k <= p.degree; ++k) {
    const double integer = std::ldexp(p.c[size_t(k)], -lowest);  // exact unless it overflows
    if (!std::isfinite(integer)) return std::nullopt;
    out.c.emplace_back(integer);
  }
  return out;
}

std::vector<mpz_class> product(const std::vector<mpz_class>& f, const std::vector<mpz_class>& g) {
  std::vector<mpz_class> p(f.size() + g.size() - 1);
  for (std::size_t i = 0; i < f.size(); ++i)
    for (std::size_t j = 0; j < g.size(); ++j)
      mpz_addmul(p[i + j].get_mpz_t(), f[i].get_mpz_t(), g[j].get_mpz_t());
  return p;
}

/// F, or a positive multiple of it: its roots and signs are F's, which is all the exact path
/// asks of it. Built on integers (products without the gcds of rational ones), p1 q1 and p2 q2
/// each an integer polynomial times a power of two, the one with the higher power shifted down
/// to the other's.
RationalPolynomial rational(const ExactPolynomial& f) {
  const auto p1 = scaled_integers(f.p1), q1 = scaled_integers(f.q1);
  const auto p2 = scaled_integers(f.p2), q2 = scaled_integers(f.q2);
  if (!p1 || !q1 || !p2 || !q2) {
    RationalPolynomial r = rational(f.p1) * rational(f.q1) - rational(f.p2) * rational(f.q2);
    return f.sign < 0 ? RationalPolynomial{} - r : r;
  }
  std::vector<mpz_class> first = product(p1->c, q1->c), second = product(p2->c, q2->c);
  const long e1 = p1->exponent + q1->exponent, e2 = p2->exponent + q2->exponent;
  const long lowest = std::min(e1, e2);
  for (mpz_class& x : first) mpz_mul_2exp(x.get_mpz_t(), x.get_mpz_t(), mp_bitcnt_t(e1 - lowest));
  for (mpz_class& x : second) mpz_mul_2exp(x.get_mpz_t(), x.get_mpz_t(), mp_bitcnt_t(e2 - lowest));
  std::vector<mpq_class> c(std::max(first.size(), second.size()));
  for (std::size_t k = 0; k < c.size(); ++k) {
    mpz_class x = 0;
    if (k < first.size()) x += first[k];
    if (k < second.size()) x -= second[k];
    c[k] = f.sign < 0 ? mpz_class(-x) : x;
  }
  return RationalPolynomial(std::move(c));
}

/// Sign of f just after the rational x: the first derivative that does not vanish there.
int sign_after_at(const RationalPolynomial& f, const mpq_class& x) {
  if (f.is_zero()) return 0;
  if (const int s = sgn(f(x)); s != 0) return s;
  for (RationalPolynomial d = f.derivative(); !d.is_zero(); d = d.derivative())
    if (const int s = sgn(d(x)); s != 0) return s;
  return 0;
}

/// exact_sign_after, with F's rational polynomial when the caller has built it already.
int sign_after_using(const ExactPolynomial& f, double s, const RationalPolynomial* built) {
  // F lies between the envelopes' Horner values (s >= 0): where one of them clears zero on its
  // side, F(s) has that sign (most times a search asks about are a few ulps from the crossing,
  // but the window's start and the bracket's end are not).
  if (s >= 0) {
    const ExactPolynomial::Envelopes& e = f.envelopes();
    if (e.lower(s) > 0) return 1;
    if (e.upper(s) < 0) return -1;
  }
  const int filtered = filtered_sign(f, s);
  if (filtered != 2) return filtered;
  return sign_after_at(built != nullptr ? *built : rational(f), mpq_class(s));
}

/// The smallest double >= x.
double double_at_or_above(const mpq_class& x) {
  double d = x.get_d();  // truncates towards zero
  while (mpq_class(d) < x) d = std::nextafter(d, kInf);
  return d;
}

/// A double beyond every real root of f (Cauchy's bound 1 + max |c_k / c_n|, doubled).
double root_bound(const RationalPolynomial& f) {
  mpq_class largest = 0;
  const mpq_class lead = abs(f.c.back());
  for (size_t k = 0; k + 1 < f.c.size(); ++k)
    largest = std::max(largest, mpq_class(abs(f.c[k]) / lead));
  const double b = 2 * (1 + largest.get_d()) + 1;
  return std::isfinite(b) ? b : std::numeric_limits<double>::max();
}

/// exact_first_failure by exact root isolation over (s_now, s_end] (f holds just after s_now).
std::optional<double> isolated_failure(const ExactPolynomial& F, double s_now, double s_end) {
  const RationalPolynomial f = rational(F);
  if (f.is_zero()) return std::nullopt;
  const double end =
      std::isfinite(s_end) ? s_end : std::max(root_bound(f), std::nextafter(s_now, kInf));
  std::vector<IsolatedRoot> roots = isolate_roots(f, mpq_class(s_now), mpq_class(end));
  for (IsolatedRoot& r : roots) {
    // The sign between this root and the next: at the interval's upper end when the root is
    // irrational, else just after the rational root. The upper end is no root of the deflated
    // polynomial the interval isolates a root of, but it can be one of f: a root of f at s_end
    // is divided out before isolation (a certificate whose pair touches exactly at the end of
    // its segment). Then f's sign there is 0, and read as "no failure" it hid the crossing
    // inside; the interval is halved until its upper end is no root of f either.
    while (!r.is_rational() && sgn(f(r.hi)) == 0) r.refine();
    const int after = r.is_rational() ? sign_after_at(f, r.lo) : sgn(f(r.hi));
    if (after >= 0) continue;  // a - to + change, or a touch from +
    // f < 0 from r to the next root: the first double at or after r, if one lies before it.
    r.refine_to(mpq_class(std::max(std::abs(r.hi.get_d()), 1e-300) * 0x1p-80));
    double t = double_at_or_above(r.lo);
    for (int k = 0; k < 8 && t <= end; ++k, t = std::nextafter(t, kInf))
      if (t > s_now && sign_after_using(F, t, &f) < 0) return t;
  }
  return std::nullopt;
}

Polynomial with_error(const Polynomial& f, const Polynomial& error, double k) {
  Polynomial out = f;
  out.degree = std::max(f.degree, error.degree);
  for (int i = 0; i <= out.degree; ++i) out.c[size_t(i)] = f.c[size_t(i)] + k * error.c[size_t(i)];
  return out;
}

/// A double t in (low, s_end] with sign_after(upper, t) < 0, galloping from low (>= 0) with
/// steps doubling from about an ulp; nullopt after 64 steps or at s_end.
std::optional<double> upper_failure_near(const Polynomial& upper, double low, double s_end) {
  double step = std::max(std::abs(low), 1e-300) * 0x1p-52;
  for (int k = 0; k < 64; ++k, step *= 2) {
    const double t = std::min(std::max(low + step, detail::next_up(low)), s_end);
    if (!(t > low)) return std::nullopt;
    if (sign_after(upper, t) < 0) return t;
    if (t == s_end) return std::nullopt;
  }
  return std::nullopt;
}

/// A guess for the exact crossing in (low, hi]: where the close polynomial's signs switch,
/// by bisection in bit space (low < hi); hi when they do not. Only the search's speed depends
/// on it: F is proven monotone on [low, hi] by then.
double close_crossing(const Polynomial& close, double low, double hi) {
  double a = detail::next_up(low), b = hi;
  if (!(a < b) || sign_after(close, a) < 0) return std::min(a, hi);
  if (sign_after(close, b) >= 0) return hi;
  while (detail::next_up(a) < b) {
    const double m = detail::bit_midpoint(a, b);
    (sign_after(close, m) < 0 ? b : a) = m;
  }
  return b;
}

/// How far F > 0 is shown from s_now on by two filters, for an F that holds just after
/// s_now >= 0: the lower bound on F's slope, `rising`, positive on [s_now, mid] (F increases from
/// its positive start, so it is positive on (s_now, mid]), and the lower envelope positive on
/// [mid, s_end] (both as real polynomials: they bound F' and F coefficient by coefficient for
/// s >= 0). A certificate rebuilt by its own event (a pixel order's pair just swapped) starts at
/// its root, where the envelopes straddle zero and the searches of exact_first_failure split the
/// window's left end down to the noise level; mid is tried from an eighth of the window down.
struct RisingStart {
  bool clear = false;  ///< F > 0 on all of (s_now, s_end]: no failure
  double from = 0;     ///< else F > 0 on (s_now, from] (from = s_now: nothing shown)
};
RisingStart rising_start(const Polynomial& rising, const Polynomial& lower, double s_now,
                         double s_end) {
  RisingStart out{false, s_now};
  const double width = s_end - s_now;
  if (!(s_now >= 0 && width > 0 && std::isfinite(width))) return out;
  for (const double fraction : {0x1p-3, 0x1p-7, 0x1p-12, 0x1p-18}) {
    const double mid = s_now + width * fraction;
    if (!(mid > s_now)) break;
    if (!holds_through(rising, s_now, mid)) continue;
    if (out.from == s_now) out.from = mid;  // the furthest mid the slope holds to
    if (holds_through(lower, mid, s_end)) {
      out.clear = true;
      return out;
    }
  }
  return out;
}

}  // namespace

const ExactPolynomial::Envelopes& ExactPolynomial::envelopes() const {
  if (m_envelopes) return *m_envelopes;
  Envelopes& f = m_envelopes.emplace();
  const int n =
      std::min(std::max(p1.degree + q1.degree, p2.degree + q2.degree), kMaxPolynomialDegree);
  f.close.degree = f.close_error.degree = n;
  for (int k = 0; k <= n; ++k) {
    // Sum of the exact products (two doubles each) with the sum's error compensated.
    double sum = 0, tail = 0, magnitude = 0;
    auto add = [&](double a, double b) {
      const Pair p = two_product(a, b);
      const Pair s = two_sum(sum, p.hi);
      sum = s.hi;
      tail += s.lo + p.lo;
      magnitude += std::abs(p.hi);
    };
    for (int i = 0; i <= k; ++i) {
      if (i <= p1.degree && k - i <= q1.degree) add(p1.c[size_t(i)], q1.c[size_t(k - i)]);
      if (i <= p2.degree && k - i <= q2.degree) add(-p2.c[size_t(i)], q2.c[size_t(k - i)]);
    }
    const double c = sum + tail;
    f.close.c[size_t(k)] = sign < 0 ? -c : c;
    // Rounding c (u |c|), the compensated sum (<= 16 u^2 magnitude), Horner on the envelopes
    // (gamma_10 |c|): 16 u |c| + 64 u^2 magnitude, with room to spare.
    f.close_error.c[size_t(k)] = 16 * kU * std::abs(c) + 64 * kU * kU * magnitude;
  }
  f.lower = with_error(f.close, f.close_error, -1);
  f.upper = with_error(f.close, f.close_error, 1);
  return f;
}

ExactPolynomial ExactPolynomial::negated() const {
  ExactPolynomial g(p1, q1, p2, q2, -sign);
  if (m_envelopes) {
    Envelopes& e = g.m_envelopes.emplace();
    e.close = -m_envelopes->close;
    e.close_error = m_envelopes->close_error;
    // (-c) -/+ e rounds to the negation of c +/- e.
    e.lower = -m_envelopes->upper;
    e.upper = -m_envelopes->lower;
  }
  return g;
}

std::shared_ptr<const ExactPolynomial> exact_product_difference(const Polynomial& p1,
                                                                const Polynomial& q1,
                                                                const Polynomial& p2,
                                                                const Polynomial& q2, int sign) {
  return std::make_shared<const ExactPolynomial>(p1, q1, p2, q2, sign);
}

std::shared_ptr<const ExactPolynomial> exact_negated(const ExactPolynomial& f) {
  return std::make_shared<const ExactPolynomial>(f.negated());
}

int exact_sign_after(const ExactPolynomial& f, double s) {
  return sign_after_using(f, s, nullptr);
}

std::optional<double> exact_first_failure(const ExactPolynomial& F, double s_now, double s_end) {
  if (exact_sign_after(F, s_now) < 0) return s_now;
  if (!(s_end > s_now)) return std::nullopt;
  // F lies between the envelopes (s >= 0). Invariant: F > 0 just after `from` and at every
  // double of (s_now, from]. Each round either decides, or proves F > 0 up to where the lower
  // envelope holds again, or gives up to exact isolation.
  const ExactPolynomial::Envelopes& e = F.envelopes();
  const Polynomial& lower = e.lower;
  const Polynomial& upper = e.upper;
  const Polynomial rising = with_error(e.close.derivative(), e.close_error.derivative(), -2);
  const Polynomial falling = -with_error(e.close.derivative(), e.close_error.derivative(), 2);
  // From a root the search starts where F is shown positive up to, past the noise.
  const RisingStart start = rising_start(rising, lower, s_now, s_end);
  if (start.clear) return std::nullopt;
  double from = start.from;
  auto negative = [&](double t) { return exact_sign_after(F, t) < 0; };
  // The proofs below read "no failure before" from Bernstein searches on the envelopes and the
  // slope's; a search that passed over a stretch at its noise level proves nothing there (the
  // lower envelope of a near double root of F dips below zero by less than its Bernstein
  // rounding, and F with it): exact isolation decides then.
  bool noise = false;
  auto holds = [&](const Polynomial& g, double a, double b) {
    return !first_failure(g, a, b, noise) && !noise;
  };
  for (int round = 0; round < 8; ++round) {
    // F > 0 at every double of (from, low); F < 0 just after `high`.
    const std::optional<double> low = first_failure(lower, from, s_end, noise);
    if (noise) break;
    if (!low) return std::nullopt;
    // The upper envelope fails at low (then F does), or a little after it, where the close
    // polynomial crosses: galloping on its signs from low finds a double where it has failed
    // (F < 0 just after it) in a few steps, sparing its search over the whole window.
    if (sign_after(upper, *low) < 0) return low;
    std::optional<double> high = upper_failure_near(upper, *low, s_end);
    if (!high) {
      high = first_failure(upper, from, s_end);
      if (high && *high == *low) return low;
    }
    // Without `high`: up to where the lower envelope holds again (F > 0 there).
    const std::optional<double> back = high ? high : first_failure(-lower, *low, s_end);
    const double hi = back ? *back : s_end;
    if (!std::isfinite(hi) || hi < *low) break;
    if (sign_after(falling, *low) > 0 &&
        (holds_through(falling, *low, hi) || holds(falling, *low, hi))) {
      // F decreasing on [low, hi]: one crossing at most, pinned down by the exact sign from
      // the close polynomial's own failure.
      if (negative(*low)) return low;
      if (!negative(hi)) {
        if (high) break;
        if (!back) return std::nullopt;  // F > 0 up to s_end
        from = hi;
        continue;
      }
      const double guess = close_crossing(e.close, *low, hi);
      const double step = std::max(std::abs(guess), 1e-300) * 0x1p-52;
      const std::optional<double> r = detail::first_negative_near(
          negative, guess, *low, hi, step, std::numeric_limits<int>::max());
      if (r) return r;
      break;
    }
    // F increasing on [low, hi]: positive there (it is just before low, or after from).
    if (high || !(sign_after(rising, *low) > 0 && holds(rising, *low, hi))) break;
    if (!back) return std::nullopt;  // F > 0 up to s_end
    from = hi;
  }
  return isolated_failure(F, s_now, s_end);
}

namespace {
/// e[i + j] += |p1_i q1_j| + |p2_i q2_j| for i <= dp, j <= dq, i + j <= the maximum degree, in
/// that order (pairs summed, so that swapping (p1, q1) with (p2, q2) gives the same bits).
/// Inlined, so that a call with constant bounds (a depth certificate's N by D) is unrolled.
[[gnu::always_inline]] inline void add_product_magnitudes(const Polynomial& p1,
                                                          const Polynomial& q1,
                                                          const Polynomial& p2,
                                                          const Polynomial& q2, int dp, int dq,
                                                          Polynomial& e) {
  for (int i = 0; i <= dp; ++i)
    for (int j = 0; j <= dq && i + j <= kMaxPolynomialDegree; ++j)
      e.c[size_t(i + j)] +=
          std::abs(p1.c[size_t(i)] * q1.c[size_t(j)]) + std::abs(p2.c[size_t(i)] * q2.c[size_t(j)]);
}
}  // namespace

Polynomial product_difference_error(const Polynomial& p1, const Polynomial& q1,
                                    const Polynomial& p2, const Polynomial& q2) {
  Polynomial e;
  e.degree = std::min(std::max(p1.degree + q1.degree, p2.degree + q2.degree), kMaxPolynomialDegree);
  const int dp = std::max(p1.degree, p2.degree), dq = std::max(q1.degree, q2.degree);
  if (dp == 3 && dq == 2)
    add_product_magnitudes(p1, q1, p2, q2, 3, 2, e);
  else
    add_product_magnitudes(p1, q1, p2, q2, dp, dq, e);
  // Forming: at most 4 products summed and one subtraction per coefficient (gamma_5); Horner
  // on the envelopes: gamma_10 of the same magnitudes. 64 u leaves a factor 4 for the rounding
  // of these bounds and of the envelopes' own coefficients.
  for (double& c : e.c) c *= 64 * kU;
  return e;
}

bool decided_despite(const Polynomial& f, const Polynomial& error, double s_now, double s_end,
                     EnvelopeVouch* vouch) {
  // Both ways: a structure that swaps the pair schedules -f, computed from the same call.
  const Polynomial lower = with_error(f, error, -1), upper = with_error(f, error, 1);
  EnvelopeVouch seen;
  auto decided = [&](const Polynomial& below, const Polynomial& above, int orientation) {
    // first_failure returns s_now exactly when sign_after is negative there; else the filter,
    // which decides only where first_failure(below) finds no failure either: most depth
    // certificates hold through their segment one way and are broken now the other.
    if (sign_after(below, s_now) < 0) return sign_after(above, s_now) < 0;
    if (holds_through(below, s_now, s_end)) return true;
    // A caller that takes a vouch (a structure that looks at the pair again where it ends) is
    // spared the search for the envelope's failure when the envelope holds through the first
    // half, quarter, ... or thirty-second of the window: most pairs of a pixel part before then.
    // The pairs whose envelopes fail at one double go to the exact path with the others.
    if (vouch != nullptr && std::isfinite(s_end)) {
      double h = s_end - s_now;
      for (int k = 0; k < 5; ++k) {
        h *= 0.5;
        if (const double until = s_now + h; until > s_now && holds_through(below, s_now, until)) {
          seen = {orientation, s_now, until};
          return false;
        }
      }
    }
    const std::optional<double> low = first_failure(below, s_now, s_end);
    if (!low) return true;
    // The exact polynomial lies above `below`: it holds at every double before low.
    seen = {orientation, s_now, *low};
    // first_failure answers a double where sign_after is negative, so `above` can fail first at
    // low only if it is broken there: most undecided certificates are spared its search.
    if (sign_after(above, *low) >= 0) return false;
    const std::optional<double> high = first_failure(above, s_now, s_end);
    return high && *high == *low;
  };
  bool both = decided(lower, upper, 1);
  // -f's envelopes are -upper and -lower, whose signs are the negated ones (Horner's value and
  // the Taylor shift negate exactly): the common case, -f broken now, needs neither polynomial.
  if (both) both = sign_after(upper, s_now) > 0 ? sign_after(lower, s_now) > 0
                                                : decided(-upper, -lower, -1);
  if (!both && vouch != nullptr) *vouch = seen;
  return both;
}

}  // namespace kinray
