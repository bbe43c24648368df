// The pixel orders' range filter (kinetic/grid/pixel_depth_order.h): polynomial_range bounds the
// exact values of a polynomial over a window, and depth_order_apart orders two triangles only
// where their exact depths are apart at every instant of it. References in GMP rationals.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "kinetic/core/rational_polynomial.h"
#include "kinetic/grid/pixel_depth_order.h"

namespace kinray {
namespace {

RationalPolynomial rational(const Polynomial& p) {
  std::vector<mpq_class> c;
  for (int k = 0; k <= p.degree; ++k) c.emplace_back(p.c[size_t(k)]);
  return RationalPolynomial(std::move(c));
}

// The window's rational points: both ends and evenly spaced ones between, where the extremes
// of a cubic are approached closely enough for a bound that could be off by a rounding to show.
std::vector<mpq_class> points(double a, double b) {
  std::vector<mpq_class> out;
  const mpq_class lo(a), hi(b);
  for (int i = 0; i <= 64; ++i) out.push_back(lo + (hi - lo) * mpq_class(i, 64));
  return out;
}

TEST(PixelDepthOrder, PolynomialRangeHoldsTheExactValues) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coef(-3, 3), unit(0, 1);
  std::uniform_int_distribution<int> exponent(-30, 30);
  for (int i = 0; i < 400; ++i) {
    const double scale = std::ldexp(1.0, exponent(rng));
    Polynomial p{coef(rng) * scale, coef(rng) * scale, coef(rng) * scale, coef(rng) * scale};
    if (i % 4 == 0) {  // cancellation: a value near zero on the window
      const double r = unit(rng);
      p = Polynomial{-r, 1} * Polynomial{-r - 1e-9, 1} * Polynomial{coef(rng), 1};
    }
    const double a = unit(rng) * (i % 3 == 0 ? 1e-3 : 1), b = a + unit(rng) * 2 + 1e-12;
    const detail::ValueRange range = detail::polynomial_range<3>(p.c.data(), a, b - a);
    const RationalPolynomial exact = rational(p);
    for (const mpq_class& s : points(a, b)) {
      const mpq_class v = exact(s);
      ASSERT_GE(v, mpq_class(range.lo)) << i;
      ASSERT_LE(v, mpq_class(range.hi)) << i;
    }
    Polynomial q{coef(rng) * scale, coef(rng) * scale, coef(rng) * scale};
    q.degree = 2;
    const detail::ValueRange quadratic = detail::polynomial_range<2>(q.c.data(), a, b - a);
    for (const mpq_class& s : points(a, b)) {
      ASSERT_GE(rational(q)(s), mpq_class(quadratic.lo)) << i;
      ASSERT_LE(rational(q)(s), mpq_class(quadratic.hi)) << i;
    }
  }
}

// Depths z = N / D of two triangles along one ray as the grid builds them (N cubic, D
// quadratic), layers from far apart to touching: where the filter orders them, the exact
// certificate's sign sign(D_A D_B) (N_B D_A - N_A D_B) is that order at every point of the window;
// and it does order layers that are clearly apart.
TEST(PixelDepthOrder, ApartOnlyWhereTheExactDepthsAre) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> coef(-1, 1), unit(0, 1);
  int decided = 0, far_layers = 0, far_decided = 0;
  for (int i = 0; i < 600; ++i) {
    DepthPolynomials a, b;
    a.denominator = Polynomial{1 + unit(rng), 0.2 * coef(rng), 0.2 * coef(rng)};
    b.denominator = Polynomial{-(1 + unit(rng)), 0.2 * coef(rng), 0.2 * coef(rng)};  // one facing away
    a.denominator.degree = b.denominator.degree = 2;
    const double za = 5 + coef(rng), gap = i % 3 == 0 ? 2.0 : (i % 3 == 1 ? 1e-3 : 1e-14);
    // N = z D plus a small cubic wobble: depth near za (a) and za + gap (b); the wobble a
    // hundredth of the gap, at most a hundredth.
    const double w = 0.01 * std::min(gap, 1.0);
    const Polynomial wobble{0, w * coef(rng), w * coef(rng), w * coef(rng)};
    a.numerator = Polynomial{za} * a.denominator + wobble;
    b.numerator = Polynomial{za + gap} * b.denominator - wobble;
    a.numerator.degree = b.numerator.degree = 3;
    const double s0 = unit(rng) * 0.5, s1 = s0 + 0.05 + unit(rng) * 0.5;
    const int apart = detail::depth_order_apart(a, b, s0, s1);
    EXPECT_EQ(detail::depth_order_apart(b, a, s0, s1), -apart) << i;
    far_layers += gap == 2.0;
    if (apart == 0) continue;
    ++decided;
    far_decided += gap == 2.0;
    const RationalPolynomial na = rational(a.numerator), da = rational(a.denominator);
    const RationalPolynomial nb = rational(b.numerator), db = rational(b.denominator);
    for (const mpq_class& s : points(s0, s1)) {
      const mpq_class dav = da(s), dbv = db(s);
      const mpq_class f = (nb(s) * dav - na(s) * dbv) * (dav * dbv > 0 ? 1 : -1);
      ASSERT_EQ(sgn(f), apart) << i;
    }
  }
  EXPECT_EQ(far_decided, far_layers);   // two units apart: always told
  EXPECT_GE(decided, 2 * far_layers);    // and the millimetre gaps too
}

}  // namespace
}  // namespace kinray
