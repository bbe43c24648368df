#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "kinetic/core/certificate_schedule.h"
#include "kinetic/core/certificate_time.h"
#include "kinetic/core/double_steps.h"
#include "kinetic/core/root_finding.h"

namespace kinray {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Polynomial linear_factor(double root) { return Polynomial{-root, 1}; }

Polynomial from_roots(std::initializer_list<double> roots, double lead = 1) {
  Polynomial p(lead);
  for (double r : roots) p = p * linear_factor(r);
  return p;
}

TEST(RootFinding, SignAfter) {
  EXPECT_EQ(sign_after(Polynomial{0, 0}, 1.0), 0);
  EXPECT_EQ(sign_after(Polynomial{1}, 1.0), 1);
  EXPECT_EQ(sign_after(Polynomial{0, -1}, 0.0), -1);     // -s at 0
  EXPECT_EQ(sign_after(Polynomial{0, 0, 1}, 0.0), 1);    // s^2 at 0
  EXPECT_EQ(sign_after(Polynomial{0, 0, 0, -2}, 0.0), -1);  // -2 s^3 at 0
  EXPECT_EQ(sign_after(from_roots({1, 2}), 1.0), -1);
  EXPECT_EQ(sign_after(from_roots({1, 2}), 2.0), 1);
}

TEST(RootFinding, KnownLinearFactors) {
  // -(s-1)(s-2)(s-3): + on [0,1), fails at 1, back at 2, fails again at 3.
  const Polynomial f = from_roots({1, 2, 3}, -1);
  const auto r = first_failure(f, 0, 10);
  ASSERT_TRUE(r);
  EXPECT_NEAR(*r, 1, 1e-14);
  EXPECT_LT(sign_after(f, *r), 0);
  const auto r2 = first_failure(f, 2.5, 10);
  ASSERT_TRUE(r2);
  EXPECT_NEAR(*r2, 3, 1e-14);
  const std::vector<double> all = sign_changes(f, 0, 10);
  ASSERT_EQ(all.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(all[i], i + 1, 1e-14);
  // Degree 8 with roots 1..8, + before 1.
  const Polynomial g = from_roots({1, 2, 3, 4, 5, 6, 7, 8});
  const std::vector<double> roots8 = sign_changes(g, 0, kInf);
  ASSERT_EQ(roots8.size(), 8u);
  for (int i = 0; i < 8; ++i) EXPECT_NEAR(roots8[i], i + 1, 1e-10);
  EXPECT_NEAR(*first_failure(g, 0, kInf), 1, 1e-13);
  EXPECT_NEAR(*first_failure(g, 2.5, kInf), 3, 1e-12);  // g < 0 on (1,2): from 2.5 it is +
  // No failure when the crossing is - to + only.
  EXPECT_FALSE(first_failure(from_roots({1}), 1.0, 5));
}

TEST(RootFinding, ClusteredRoots) {
  // Roots 1e-9 apart, expressed around the cluster (the caller picks the local origin).
  const Polynomial f = from_roots({0, 1e-9, 2e-9}, -1);  // + before 0
  const auto r = first_failure(f, -1, 1);
  ASSERT_TRUE(r);
  EXPECT_NEAR(*r, 0, 1e-20);
  EXPECT_EQ(first_failure(f, 0.5e-9, 1), 0.5e-9);  // already broken between the first two
  const auto r2 = first_failure(f, 1.5e-9, 1);
  ASSERT_TRUE(r2);
  EXPECT_NEAR(*r2, 2e-9, 1e-22);
  const std::vector<double> all = sign_changes(f, -1, 1);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_NEAR(all[1], 1e-9, 1e-22);
  EXPECT_NEAR(all[2], 2e-9, 1e-22);
  // Four roots 1e-9 apart near t = 5, certificate written about the origin 5.
  const Polynomial g = from_roots({1e-9, 2e-9, 3e-9, 4e-9});  // + before the cluster
  const auto r3 = first_failure(g, -5, 5);
  ASSERT_TRUE(r3);
  EXPECT_NEAR(5 + *r3, 5 + 1e-9, 1e-15);
}

TEST(RootFinding, MultipleRoots) {
  // Double root: a touch, not a failure. Dyadic roots keep the coefficients exact.
  const Polynomial touch = from_roots({0.5, 0.5});
  EXPECT_FALSE(first_failure(touch, 0, 10));
  EXPECT_TRUE(sign_changes(touch, 0, 10).empty());
  const Polynomial touch_then_fail = from_roots({1, 1, 3}, -1);
  const auto r = first_failure(touch_then_fail, 0, 10);
  ASSERT_TRUE(r);
  EXPECT_NEAR(*r, 3, 1e-13);
  // Triple root: a failure (located to the cube root of the rounding noise).
  const Polynomial triple = from_roots({1, 1, 1}, -1);
  const auto r3 = first_failure(triple, 0, 10);
  ASSERT_TRUE(r3);
  EXPECT_NEAR(*r3, 1, 1e-4);
  EXPECT_LT(sign_after(triple, *r3), 0);
  // Quadruple: touch.
  EXPECT_FALSE(first_failure(from_roots({0.25, 0.25, 0.25, 0.25}), 0, 1));
}

TEST(RootFinding, RootsAtTheIntervalEnds) {
  // Root exactly at s_now with the sign after + : not a failure now.
  const Polynomial start_up = from_roots({0, 2}, -1);  // 2s - s^2
  const auto r = first_failure(start_up, 0, 10);
  ASSERT_TRUE(r);
  EXPECT_EQ(*r, 2);
  // Root at s_now with the sign after - : already broken, fails now.
  EXPECT_EQ(first_failure(Polynomial{0, -1}, 0, 1), 0.0);
  EXPECT_EQ(first_failure(from_roots({0.5, 2}), 0.5, 1), 0.5);
  // Root exactly at s_end: reported; a touch at s_end is not.
  EXPECT_EQ(first_failure(Polynomial{1, -1}, 0, 1), 1.0);
  EXPECT_EQ(first_failure(from_roots({1, -1}, -1), 0, 1), 1.0);
  EXPECT_FALSE(first_failure(from_roots({1, 1}), 0, 1));
  // Root just beyond s_end: none.
  EXPECT_FALSE(first_failure(Polynomial{1, -1}, 0, std::nextafter(1.0, 0.0)));
  EXPECT_FALSE(first_failure(from_roots({1, 3}, 1), 0, std::nextafter(1.0, 0.0)));
  // Empty interval.
  EXPECT_FALSE(first_failure(Polynomial{1, -1}, 0.5, 0.5));
}

TEST(RootFinding, TinyLeadingCoefficients) {
  // 1 - s + 1e-20 s^2: roots ~1 and ~1e20.
  const Polynomial f{1, -1, 1e-20};
  EXPECT_NEAR(*first_failure(f, 0, kInf), 1, 1e-15);
  // 1 + s - 1e-20 s^2: the only failure is near 1e20.
  const Polynomial g{1, 1, -1e-20};
  const auto r = first_failure(g, 0, kInf);
  ASSERT_TRUE(r);
  EXPECT_NEAR(*r / 1e20, 1, 1e-12);
  EXPECT_FALSE(first_failure(g, 0, 1e19));
  // 1 + s - 1e-200 s^8: root where s^7 = 1e200 (beyond the direct search range, via 1/w).
  const Polynomial h{1, 1, 0, 0, 0, 0, 0, 0, -1e-200};
  const auto rh = first_failure(h, 0, kInf);
  ASSERT_TRUE(rh);
  EXPECT_NEAR(std::log10(*rh), 200.0 / 7.0, 1e-9);
  // A linear certificate with an infinite horizon.
  EXPECT_NEAR(*first_failure(Polynomial{1, -1e-6}, 0, kInf), 1e6, 1e-9);
  EXPECT_FALSE(first_failure(Polynomial{1, 1e-300}, 0, kInf));
}

TEST(RootFinding, ZeroAndConstantPolynomials) {
  EXPECT_FALSE(first_failure(Polynomial{}, 0, 1));
  EXPECT_FALSE(first_failure(Polynomial{0, 0, 0}, 0, kInf));
  EXPECT_TRUE(sign_changes(Polynomial{0, 0}, 0, 1).empty());
  EXPECT_FALSE(first_failure(Polynomial{2}, 0, kInf));
  EXPECT_EQ(first_failure(Polynomial{-2}, 3, kInf), 3.0);
}

TEST(RootFinding, FastPathIsCounted) {
  root_stats() = {};
  const Polynomial far = from_roots({5, 6, 7}, -1);  // + on [0, 5)
  for (int i = 0; i < 10; ++i) EXPECT_FALSE(first_failure(far, 0, 1));
  EXPECT_EQ(root_stats().calls, 10u);
  EXPECT_EQ(root_stats().fast_path_no_root, 10u);
  EXPECT_EQ(root_stats().subdivisions, 0u);
}

// ---- Randomised comparison against a slow brute force in long double -----------------------
//
// Tolerances. first_failure's decisions rest on certified Bernstein signs (error bound
// (8n+16) u M, M the magnitude polynomial sum |c_k| |s|^k, u = 2^-53, so < 9e-15 M for n = 8)
// and on Horner's evaluation (error < 2n u M < 2e-15 M). The brute force evaluates in long double
// (64-bit mantissa, error ~ 1e-18 M) and calls a sample "certain" when |f| > 1e-12 M: 100 times
// our error bounds, so a certain sample's sign is the sign both computations see. Checks:
//  (a) no missed failure: if a certain negative sample exists after s_now (f starts +), a failure
//      is reported no later than the first such sample;
//  (b) no false failure: f is not certainly positive at the reported time (its evaluated sign
//      just after is -, so the true value is below Horner's error bound);
//  (c) sign_changes brackets every certain sign change of consecutive samples, and every change
//      it reports sits where |f| is within noise.
// Sign changes hidden between two samples (a dip narrower than the sample step) are beyond the
// brute force's resolution; they may be reported by us, and (b) still checks them.

long double eval_ld(const Polynomial& f, long double s) {
  long double acc = f.c[f.degree];
  for (int k = f.degree - 1; k >= 0; --k) acc = acc * s + f.c[k];
  return acc;
}
long double magnitude(const Polynomial& f, long double s) {
  long double acc = std::fabs(f.c[f.degree]);
  const long double as = std::fabs(s);
  for (int k = f.degree - 1; k >= 0; --k) acc = acc * as + std::fabs(f.c[k]);
  return acc;
}
int certain_sign(const Polynomial& f, long double s) {
  const long double v = eval_ld(f, s), m = magnitude(f, s);
  if (std::fabs(v) <= 1e-12L * m) return 0;
  return v > 0 ? 1 : -1;
}

Polynomial random_test_polynomial(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> degree_dist(1, 8);
  std::uniform_real_distribution<double> u(-1, 1);
  const int degree = degree_dist(rng);
  Polynomial p;
  switch (rng() % 3) {
    case 0: {  // random coefficients, random scales
      p.degree = degree;
      for (int k = 0; k <= degree; ++k) p.c[k] = u(rng) * std::pow(10.0, 2 * u(rng));
      break;
    }
    case 1: {  // product of linear factors with roots in [-1, 3]
      p = Polynomial(u(rng) < 0 ? -1.0 : 1.0);
      for (int k = 0; k < degree; ++k) p = p * linear_factor(1 + 2 * u(rng));
      break;
    }
    default: {  // linear and quadratic factors (some with complex roots), some close pairs
      p = Polynomial(u(rng) * 3);
      int d = 0;
      while (d < degree) {
        if (d + 2 <= degree && rng() % 2) {
          const double centre = 1 + 2 * u(rng);
          const double spread = std::pow(10.0, -6 * std::fabs(u(rng))) * u(rng);
          // (s - centre)^2 - spread: real pair if spread > 0, complex otherwise.
          p = p * Polynomial{centre * centre - spread, -2 * centre, 1};
          d += 2;
        } else {
          p = p * linear_factor(1 + 2 * u(rng));
          d += 1;
        }
      }
    }
  }
  return p;
}

double fujiwara(const Polynomial& f) {
  const Polynomial p = f.trimmed();
  double b = 0;
  for (int k = 1; k <= p.degree; ++k)
    b = std::max(b, std::pow(std::fabs(p.c[p.degree - k] / p.c[p.degree]) / (k == p.degree ? 2 : 1),
                             1.0 / k));
  return 2 * b;
}

TEST(RootFinding, RandomisedAgainstBruteForce) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(0, 1);
  constexpr int kPolynomials = 100000;
  constexpr int kSamples = 400;
  int failures_found = 0, failures_bf = 0, broken_now = 0, changes_checked = 0, tail_cases = 0;
  for (int trial = 0; trial < kPolynomials; ++trial) {
    const Polynomial f = random_test_polynomial(rng);
    if (f.is_zero()) continue;
    const double s_now = -1 + 2 * u(rng);
    const bool infinite = rng() % 10 == 0;
    const double s_end = infinite ? kInf : s_now + 0.1 + 4 * u(rng);
    double reach = s_end;
    if (infinite) {
      reach = std::max(s_now, fujiwara(f)) + 1;
      if (!(reach < 1e6)) reach = s_now + 1e6;  // deep tails: checked by the exact tests
      ++tail_cases;
    }
    const auto r = first_failure(f, s_now, s_end);
    SCOPED_TRACE(testing::Message() << "trial " << trial << " degree " << f.degree << " s_now "
                                    << s_now << " s_end " << s_end);
    if (sign_after(f, s_now) < 0) {
      ++broken_now;
      ASSERT_TRUE(r);
      ASSERT_EQ(*r, s_now);
      const int cs = certain_sign(f, s_now);
      ASSERT_NE(cs, 1) << "sign_after disagrees with a certain positive value";
      continue;
    }
    // Brute force: samples in (s_now, reach].
    long double first_negative = 0;
    bool has_negative = false;
    std::vector<std::pair<long double, int>> certain;
    for (int i = 1; i <= kSamples; ++i) {
      const long double s = s_now + (static_cast<long double>(reach) - s_now) * i / kSamples;
      const int cs = certain_sign(f, s);
      if (cs != 0) certain.push_back({s, cs});
      if (cs < 0 && !has_negative) first_negative = s, has_negative = true;
    }
    if (has_negative) {
      ++failures_bf;
      ASSERT_TRUE(r) << "missed failure before " << static_cast<double>(first_negative);
      ASSERT_LE(*r, std::nextafter(static_cast<double>(first_negative), kInf));
    }
    if (r) {
      ++failures_found;
      ASSERT_GT(*r, s_now);
      ASSERT_LE(*r, s_end);
      ASSERT_LT(sign_after(f, *r), 0);
      ASSERT_NE(certain_sign(f, *r), 1) << "false failure at " << *r;
    }
    // sign_changes on a tenth of the cases (it walks the whole interval).
    if (trial % 10 == 0) {
      const std::vector<double> changes = sign_changes(f, s_now, infinite ? kInf : s_end);
      for (double c : changes) ASSERT_NE(certain_sign(f, c), -sign_after(f, c)) << c;
      for (size_t i = 0; i + 1 < certain.size(); ++i) {
        if (certain[i].second == certain[i + 1].second) continue;
        ++changes_checked;
        const double lo = static_cast<double>(certain[i].first);
        const double hi = static_cast<double>(certain[i + 1].first);
        bool bracketed = false;
        for (double c : changes)
          bracketed |= c >= std::nextafter(lo, -kInf) && c <= std::nextafter(hi, kInf);
        ASSERT_TRUE(bracketed) << "sign change in [" << lo << ", " << hi << "] not reported";
      }
    }
  }
  // The generator must exercise all branches.
  EXPECT_GT(failures_bf, kPolynomials / 10);
  EXPECT_GT(broken_now, kPolynomials / 10);
  EXPECT_GT(tail_cases, kPolynomials / 20);
  EXPECT_GT(changes_checked, 1000);
  RecordProperty("failures_found", failures_found);
}

TEST(RootFinding, HoldsThroughFilterDecidesOnlyCertainWindows) {
  // Clear cases: decided without the exact search.
  EXPECT_TRUE(holds_through(Polynomial{1, 1, 0}, 0, 1));           // increasing, positive
  EXPECT_TRUE(holds_through(Polynomial{1, 0, -0.5}, 0, 1));        // opens downwards, ends > 0
  EXPECT_TRUE(holds_through(from_roots({-1, 2, 3}), 1, 1.5));  // cubic, decreasing there
  EXPECT_TRUE(holds_through(from_roots({-1, 2, 3, 4, 5}), 1, 1.1));  // quintic, as depth ones
  EXPECT_FALSE(holds_through(from_roots({-1, 1.05, 3, 4, 5}), 1, 1.1));  // a root inside
  // A root in the window, a dip between positive ends, or a root at the window's start: never.
  EXPECT_FALSE(holds_through(from_roots({0.5, 2}), 0, 1));
  EXPECT_FALSE(holds_through(Polynomial{0.01, -1, 1}, 0, 1));  // vertex at 0.5, f(0.5) < 0
  EXPECT_FALSE(holds_through(Polynomial{1e-30, 1, 0}, 0, 1));   // f(0) within rounding of 0
  EXPECT_FALSE(holds_through(Polynomial{1, 1, 0}, 0, kInf));
  // Against the exact search and brute-force Horner evaluation: whenever the filter decides, the
  // certificate holds at every sampled double of the window and first_failure finds no failure.
  std::mt19937_64 rng(1414);
  std::uniform_real_distribution<double> coef(-1, 1), start(-2, 2), width(0, 3);
  int decided = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    Polynomial f;
    f.degree = 1 + trial % 5;  // up to the depth certificates' 5
    for (int k = 0; k <= f.degree; ++k) f.c[size_t(k)] = coef(rng) * std::pow(10.0, -3 * (trial % 4));
    const double a = start(rng), b = a + width(rng);
    if (!holds_through(f, a, b)) continue;
    ++decided;
    EXPECT_FALSE(first_failure(f, a, b).has_value());
    for (int k = 0; k <= 64; ++k) EXPECT_GT(f(a + (b - a) * k / 64), 0);
  }
  EXPECT_GT(decided, 2000);  // the filter is not vacuous
}

// certificate_failure_time before its written-out quadratic path: the general functions, step for
// step (holds_through, first_failure_low_degree, sign_after, schedule_certificate).
double general_failure_time(const Polynomial& f, double origin, double now, double end) {
  const double s_now = now - origin;
  if (holds_through(f, s_now, end - origin)) return kInf;
  const std::optional<double> r = first_failure_low_degree(f, s_now, end - origin);
  if (!r) return kInf;
  if (*r == s_now) return now;
  double t = std::max(now, origin + *r);
  for (int k = 0; k < 16; ++k, t = detail::next_up(t))
    if (sign_after(f, t - origin) < 0) return t;
  OrderCertificate c;
  c.f = f;
  c.origin = origin;
  c.end = end;
  const detail::Schedule s = detail::schedule_certificate(c, now, 0, 0);
  return s.failure ? s.time : kInf;
}

TEST(CertificateTime, QuadraticPathIsTheGeneralArithmetic) {
  // A stored quadratic (every coverage certificate of a boundary) takes written-out operations;
  // they must give the very double the general path gives, for both signs: random quadratics
  // and the degenerate ones, roots exactly at either end of the window or one double beyond,
  // double roots, no real root, a zero or tiny leading coefficient, a zero constant term.
  std::mt19937_64 rng(1404);
  std::uniform_real_distribution<double> unit(0, 1), coef(-1, 1);
  int finite = 0, at_now = 0, kinds_seen[8] = {};
  for (int trial = 0; trial < 200000; ++trial) {
    const double origin = 4 * unit(rng), now = origin + (trial % 3 == 0 ? 0.0 : 0.1 * unit(rng));
    const double end = now + (trial % 17 == 0 ? 0.0 : 0.2 * unit(rng));
    const double s_now = now - origin, s_end = end - origin;
    auto pick = [&](int where) {
      switch (where) {
        case 0: return s_now;
        case 1: return s_end;
        case 2: return detail::next_up(s_end);
        case 3: return detail::next_down(s_now);
        default: return s_now + (s_end - s_now + 0.1) * (2 * unit(rng) - 0.5);
      }
    };
    const int kind = trial % 8;
    ++kinds_seen[kind];
    const double r1 = pick(int(rng() % 8)), r2 = kind == 1 ? r1 : pick(int(rng() % 8));
    const double lead = coef(rng) * std::pow(10.0, -double(rng() % 6));
    Polynomial f;
    f.degree = 2;
    switch (kind) {
      case 2:  // no real root: lead ((s - r1)^2 + w^2)
        f = Polynomial{lead * (r1 * r1 + 1e-6 * unit(rng)), -2 * lead * r1, lead};
        break;
      case 3:  // zero leading coefficient: a line through r1, stored with degree 2
        f = Polynomial{-lead * r1, lead, 0.0};
        break;
      case 4:  // tiny leading coefficient
        f = Polynomial{lead * r1 * r2, -lead * (r1 + r2), lead * 1e-18};
        break;
      case 5:  // zero constant term
        f = Polynomial{0.0, coef(rng), coef(rng)};
        break;
      default: f = Polynomial{lead * r1 * r2, -lead * (r1 + r2), lead};
    }
    ASSERT_EQ(f.degree, 2);
    for (int sign : {1, -1}) {
      const Polynomial g = sign > 0 ? f : -f;
      const double expected = general_failure_time(g, origin, now, end);
      const double got = certificate_failure_time(sign, f, origin, now, end);
      ASSERT_EQ(std::bit_cast<uint64_t>(got), std::bit_cast<uint64_t>(expected))
          << "trial " << trial << " sign " << sign << " f = " << f.c[0] << " + " << f.c[1]
          << " s + " << f.c[2] << " s^2, origin " << origin << ", now " << now << ", end " << end;
      if (sign > 0) {
        ASSERT_EQ(std::bit_cast<uint64_t>(certificate_failure_time(f, origin, now, end)),
                  std::bit_cast<uint64_t>(expected));
      }
      if (got == now) ++at_now;
      if (got != kInf && got != now) {
        ++finite;
        EXPECT_LT(sign_after(g, got - origin), 0);  // the event sees the change
      }
    }
  }
  // The generator reaches both answers besides "holds".
  EXPECT_GT(finite, 20000);
  EXPECT_GT(at_now, 5000);
}

TEST(CertificateTime, HoldsFromRootDecidesOnlyWhatFirstFailureDecides) {
  // Cubics that have just crossed zero upwards at s_now (the first double where sign_after is +,
  // as an orientation certificate rebuilt by its event), with their other roots behind, beyond,
  // inside the window, at its end, complex, or a double root at s_now. Whenever the filter says
  // "holds", first_failure must find no failure; it must decide the plain cases.
  std::mt19937_64 rng(1405);
  std::uniform_real_distribution<double> unit(0, 1);
  int decided = 0, plain = 0, plain_decided = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double r0 = 0.05 * unit(rng), s_end0 = r0 + 0.05 * unit(rng);
    const double lead = (unit(rng) + 0.01) * std::pow(10.0, -double(rng() % 8));
    const int kind = trial % 6;
    Polynomial f;
    switch (kind) {
      case 0: f = from_roots({r0, -1 - unit(rng), s_end0 + 0.01 + unit(rng)}, lead); break;
      case 1: {  // a failure and a recovery inside the window: positive again at its end
        const double r1 = r0 + (s_end0 - r0) * unit(rng);
        f = from_roots({r0, r1, r1 + (s_end0 - r1) * unit(rng)}, lead);
        break;
      }
      case 2: f = from_roots({r0, s_end0, s_end0 + unit(rng)}, lead); break;
      case 3: f = from_roots({r0, r0, -unit(rng)}, lead); break;
      case 4: f = from_roots({r0}, lead) * Polynomial{0.01 + unit(rng), -2 * unit(rng), 1}; break;
      default: f = from_roots({r0, -unit(rng), -unit(rng)}, lead); break;
    }
    ASSERT_EQ(f.degree, 3);
    if (f.derivative()(r0) < 0) f = -f;  // crossing upwards
    double s_now = r0;
    for (int k = 0; k < 100000 && sign_after(f, s_now) <= 0; ++k) s_now = detail::next_up(s_now);
    if (sign_after(f, s_now) <= 0) continue;
    const double s_end = std::max(s_end0, s_now);
    const bool holds = holds_from_root(f, s_now, s_end);
    if (holds) {
      ++decided;
      EXPECT_FALSE(first_failure(f, s_now, s_end).has_value())
          << "trial " << trial << " kind " << kind << " s_now " << s_now << " s_end " << s_end;
    }
    if (kind == 0 || kind == 4 || kind == 5) {
      ++plain;
      plain_decided += holds;
    }
  }
  EXPECT_GT(decided, 2000);
  EXPECT_GT(plain_decided, plain / 2);  // the filter is not vacuous where it is meant to decide
  RecordProperty("decided", decided);
  // Outside its case it says nothing.
  EXPECT_FALSE(holds_from_root(from_roots({-1, -2}), 0, 1));       // degree 2
  EXPECT_FALSE(holds_from_root(from_roots({0.5, -1, -2}), 0, 1));  // a failure inside
  EXPECT_FALSE(holds_from_root(-from_roots({-1, -2, -3}), 0, 1));  // broken now
  EXPECT_FALSE(holds_from_root(from_roots({-1, -2, -3}), -1, 1));  // s_now < 0
}

}  // namespace
}  // namespace kinray
