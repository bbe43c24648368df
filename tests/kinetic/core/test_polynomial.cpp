#include <gtest/gtest.h>

#include <cmath>
#include <iterator>
#include <random>

#include "kinetic/core/polynomial.h"

namespace kinray {
namespace {

Polynomial random_polynomial(std::mt19937_64& rng, int degree) {
  std::uniform_real_distribution<double> u(-2, 2);
  Polynomial p;
  p.degree = degree;
  for (int k = 0; k <= degree; ++k) p.c[k] = u(rng);
  return p;
}

TEST(Polynomial, ConstructionAndEvaluation) {
  const Polynomial zero;
  EXPECT_TRUE(zero.is_zero());
  EXPECT_EQ(zero.degree, 0);
  const Polynomial k(3.5);
  EXPECT_EQ(k(10.0), 3.5);
  const Polynomial p{1, -3, 2};  // 1 - 3s + 2s^2 = (1 - s)(1 - 2s)
  EXPECT_EQ(p.degree, 2);
  EXPECT_EQ(p(0.0), 1);
  EXPECT_EQ(p(1.0), 0);
  EXPECT_EQ(p(0.5), 0);
  EXPECT_EQ(p(2.0), 3);
  const Polynomial padded{1, 2, 0, 0};
  EXPECT_EQ(padded.degree, 3);
  EXPECT_EQ(padded.effective_degree(), 1);
  EXPECT_EQ(padded.trimmed().degree, 1);
  EXPECT_FALSE(padded.is_zero());
}

TEST(Polynomial, DerivativeAndArithmetic) {
  const Polynomial p{1, -3, 2};
  const Polynomial d = p.derivative();
  EXPECT_EQ(d.degree, 1);
  EXPECT_EQ(d.c[0], -3);
  EXPECT_EQ(d.c[1], 4);
  const Polynomial q{0, 1};
  const Polynomial sum = p + q, diff = p - q, prod = p * q;
  EXPECT_EQ(sum(3.0), p(3.0) + 3.0);
  EXPECT_EQ(diff(3.0), p(3.0) - 3.0);
  EXPECT_EQ(prod.degree, 3);
  EXPECT_EQ(prod(3.0), p(3.0) * 3.0);
  EXPECT_EQ((2.0 * p)(3.0), 2 * p(3.0));
  EXPECT_EQ((-p)(3.0), -p(3.0));
}

TEST(Polynomial, DifferenceIsExactlyAntisymmetricAndProductCommutative) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 1000; ++trial) {
    const Polynomial f = random_polynomial(rng, trial % 5), g = random_polynomial(rng, trial % 4);
    EXPECT_TRUE(f - g == -(g - f));
    EXPECT_TRUE(f * g == g * f);
  }
}

// operator* writes the products of degrees 1x1, 3x2 and 2x3 out at compile time: they must be the
// general loop's doubles bit for bit, signed zeros included (a coefficient -0.0 or 0.0, a term
// that rounds to zero, an effective degree below the stored one).
TEST(Polynomial, WrittenOutProductsAreTheGeneralLoopBitForBit) {
  std::mt19937_64 rng(11);
  const double specials[] = {0.0, -0.0, 1e-200, -1e-200, 1.0, -1.0, 0x1p-1074};
  auto coefficient = [&](int pick) {
    if (pick % 3 == 0) return specials[size_t(pick / 3) % std::size(specials)];
    return std::uniform_real_distribution<double>(-2, 2)(rng);
  };
  const int degrees[][2] = {{1, 1}, {3, 2}, {2, 3}, {1, 2}, {3, 3}};
  for (int trial = 0; trial < 20000; ++trial) {
    const auto& d = degrees[size_t(trial) % std::size(degrees)];
    Polynomial f, g;
    f.degree = d[0];
    g.degree = d[1];
    for (int k = 0; k <= f.degree; ++k) f.c[k] = coefficient(int(rng() % 9));
    for (int k = 0; k <= g.degree; ++k) g.c[k] = coefficient(int(rng() % 9));
    if (trial % 7 == 0) f.c[f.degree] = trial % 2 ? 1e-300 : 1.0;  // keep the degree often
    if (f.effective_degree() + g.effective_degree() > kMaxPolynomialDegree) continue;
    const Polynomial a = f * g, b = detail::general_product(f, g);
    ASSERT_EQ(a.degree, b.degree) << trial;
    for (int k = 0; k <= kMaxPolynomialDegree; ++k)
      ASSERT_EQ(std::signbit(a.c[k]), std::signbit(b.c[k])) << trial << " " << k;
    ASSERT_TRUE(a == b) << trial;
  }
}

TEST(Polynomial, ProductDegreeOverflowChecks) {
  Polynomial f;
  f.degree = 5;
  f.c[5] = 1;
  const Polynomial padded{1, 1, 0, 0, 0, 0, 0};  // degree 6 stored, effective 1
  EXPECT_EQ((f * padded).degree, 6);
  EXPECT_DEATH((void)(f * f), "kMaxPolynomialDegree");
}

TEST(Polynomial, ShiftedMatchesEvaluation) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 1000; ++trial) {
    const Polynomial f = random_polynomial(rng, 1 + trial % 8);
    const double shift = u(rng), s = u(rng);
    const Polynomial g = shifted(f, shift);
    // Rounding of the Taylor shift is relative to the magnitude sum |c_k| (|s| + |shift|)^k.
    double magnitude = 0;
    for (int k = f.degree; k >= 0; --k)
      magnitude = magnitude * (std::fabs(s) + std::fabs(shift)) + std::fabs(f.c[k]);
    EXPECT_NEAR(g(s), f(s + shift), 1e-13 * magnitude);
  }
}

TEST(Polynomial, BernsteinRoundTripEvaluateSubdivide) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int trial = 0; trial < 1000; ++trial) {
    const Polynomial f = random_polynomial(rng, trial % 9);
    // Intervals of width >= 1 inside [-1, 2]: the back conversion divides by (b - a)^k.
    const double a = -0.5 + 0.25 * u(rng), b = 1.5 + 0.25 * u(rng);
    const BernsteinPolynomial bf = to_bernstein(f, a, b);
    EXPECT_EQ(bf.degree, f.degree);
    // End coefficients interpolate; the control polygon bounds the curve (convex hull).
    // Tolerances relative to the size of the control polygon: the Bernstein to power conversion
    // has alternating sums weighted by C(n, j) C(j, i) (up to 4900 for n = 8).
    double scale = 1;
    for (int i = 0; i <= bf.degree; ++i) scale = std::max(scale, std::fabs(bf.b[i]));
    EXPECT_NEAR(bf.b[0], f(a), 1e-12 * scale);
    EXPECT_NEAR(bf.b[f.degree], f(b), 1e-12 * scale);
    const Polynomial back = to_power(bf);
    for (int k = 0; k <= f.degree; ++k) EXPECT_NEAR(back.c[k], f.c[k], 1e-9 * scale);
    const double s = a + (b - a) * 0.3;
    EXPECT_NEAR(evaluate(bf, s), f(s), 1e-12 * scale);
    const auto [left, right] = subdivide(bf, s);
    EXPECT_EQ(left.bnd, s);
    EXPECT_EQ(right.a, s);
    const double sl = a + (s - a) * 0.5, sr = s + (b - s) * 0.5;
    EXPECT_NEAR(evaluate(left, sl), f(sl), 1e-12 * scale);
    EXPECT_NEAR(evaluate(right, sr), f(sr), 1e-12 * scale);
    double lo = bf.b[0], hi = bf.b[0];
    for (int i = 0; i <= bf.degree; ++i) lo = std::min(lo, bf.b[i]), hi = std::max(hi, bf.b[i]);
    EXPECT_GE(f(s), lo - 1e-12);
    EXPECT_LE(f(s), hi + 1e-12);
  }
}

}  // namespace
}  // namespace kinray
