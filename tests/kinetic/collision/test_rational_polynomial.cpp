// Exact root isolation and signs at algebraic roots, against roots known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "kinetic/core/rational_polynomial.h"

namespace kinray {
namespace {

RationalPolynomial from_roots(std::initializer_list<mpq_class> roots) {
  RationalPolynomial p({1});
  for (const mpq_class& r : roots) p = p * RationalPolynomial::linear(-r, 1);
  return p;
}

TEST(RationalPolynomial, IsolatesEachRootOnceWithMultiplicities) {
  // (t - 1/3)(t - 1/2)^2 (t - 2): roots 1/3 and 1/2 (double) in [0, 1], 2 outside
  const RationalPolynomial p =
      from_roots({mpq_class(1, 3), mpq_class(1, 2), mpq_class(1, 2), mpq_class(2)});
  std::vector<IsolatedRoot> roots = isolate_roots(p, 0, 1);
  ASSERT_EQ(roots.size(), 2u);
  for (IsolatedRoot& r : roots) r.refine_to(mpq_class(1, 1 << 30));
  EXPECT_LE(roots[0].lo, mpq_class(1, 3));
  EXPECT_GE(roots[0].hi, mpq_class(1, 3));
  EXPECT_LE(roots[1].lo, mpq_class(1, 2));
  EXPECT_GE(roots[1].hi, mpq_class(1, 2));
}

TEST(RationalPolynomial, FindsRootsAtTheIntervalEnds) {
  const std::vector<IsolatedRoot> roots = isolate_roots(from_roots({0, 1}), 0, 1);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_TRUE(roots[0].is_rational() && roots[0].lo == 0);
  EXPECT_TRUE(roots[1].is_rational() && roots[1].lo == 1);
}

TEST(RationalPolynomial, InteriorRootBesideRootsAtTheEnds) {
  // t (t - 1/3)(t - 1): the interior root's interval must not contain the ends' roots
  std::vector<IsolatedRoot> roots = isolate_roots(from_roots({0, mpq_class(1, 3), 1}), 0, 1);
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(-1, 3), roots[1]), 0);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(0, 1), roots[1]), 1);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(mpq_class(-1, 2), 1), roots[1]), -1);
}

TEST(RationalPolynomial, IrrationalRootsAndExactSignsThere) {
  // t^2 - 1/2 has the root 1/sqrt(2) in [0, 1]
  std::vector<IsolatedRoot> roots =
      isolate_roots(RationalPolynomial({mpq_class(-1, 2), 0, 1}), 0, 1);
  ASSERT_EQ(roots.size(), 1u);
  IsolatedRoot& r = roots[0];
  // 2 t^2 - 1 vanishes there exactly (a multiple sharing the root), t - 0.7071 is positive,
  // t - 0.7072 negative.
  EXPECT_EQ(sign_at(RationalPolynomial({-1, 0, 2}), r), 0);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(mpq_class(-7071, 10000), 1), r), 1);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(mpq_class(-7072, 10000), 1), r), -1);
  // (t^2 - 1/2)(t - 3): vanishes at the root through a common factor
  EXPECT_EQ(
      sign_at(RationalPolynomial({mpq_class(-1, 2), 0, 1}) * RationalPolynomial::linear(-3, 1), r),
      0);
}

TEST(RationalPolynomial, SignsAtRootsOfQuadratics) {
  // (t - 1/3)(t - 2/3): rational roots, which no double is; signs there decided exactly
  std::vector<IsolatedRoot> roots =
      isolate_roots(RationalPolynomial({mpq_class(2, 9), -1, 1}), 0, 1);
  ASSERT_EQ(roots.size(), 2u);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(-1, 3), roots[0]), 0);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(-2, 3), roots[0]), -1);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(-2, 3), roots[1]), 0);
  EXPECT_EQ(
      sign_at(RationalPolynomial::linear(-1, 3) * RationalPolynomial::linear(-5, 1), roots[1]), -1);
  // t^2 - 1/2 plus 10^-40: not zero at 1/sqrt(2), though no double interval can tell
  std::vector<IsolatedRoot> irrational =
      isolate_roots(RationalPolynomial({mpq_class(-1, 2), 0, 1}), 0, 1);
  ASSERT_EQ(irrational.size(), 1u);
  mpq_class tiny(1);
  for (int i = 0; i < 40; ++i) tiny /= 10;
  EXPECT_EQ(sign_at(RationalPolynomial({mpq_class(-1, 2) + tiny, 0, 1}), irrational[0]), 1);
  EXPECT_EQ(sign_at(RationalPolynomial({mpq_class(-1, 2) - tiny, 0, 1}), irrational[0]), -1);
}

TEST(RationalPolynomial, SignsCloserToTheRootThanDoublesResolve) {
  // The doubles on either side of 1/sqrt(2): the floating-point filter narrows the root's
  // interval to a few ulps and cannot tell; the exact path must.
  std::vector<IsolatedRoot> roots =
      isolate_roots(RationalPolynomial({mpq_class(-1, 2), 0, 1}), 0, 1);
  ASSERT_EQ(roots.size(), 1u);
  const double above = 0.7071067811865476, below = std::nextafter(above, 0.0);
  ASSERT_GT(mpq_class(above) * mpq_class(above), mpq_class(1, 2));
  ASSERT_LT(mpq_class(below) * mpq_class(below), mpq_class(1, 2));
  EXPECT_EQ(sign_at(RationalPolynomial::linear(-mpq_class(above), 1), roots[0]), -1);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(-mpq_class(below), 1), roots[0]), 1);
  EXPECT_LE(roots[0].lo * roots[0].lo, mpq_class(1, 2));  // still isolating the root
  EXPECT_GE(roots[0].hi * roots[0].hi, mpq_class(1, 2));
  // a polynomial of huge coefficients, beyond the filter's range: decided exactly
  mpq_class huge = 1;
  mpz_mul_2exp(huge.get_num_mpz_t(), huge.get_num_mpz_t(), 2000);
  EXPECT_EQ(sign_at(RationalPolynomial({-huge, huge}), roots[0]), -1);
  // from a fresh, wide isolating interval, signs that need the interval narrowed first
  for (const auto& [value, expected] :
       {std::pair{mpq_class(7071, 10000), 1}, std::pair{mpq_class(7072, 10000), -1},
        std::pair{mpq_class(above), -1}, std::pair{mpq_class(below), 1}}) {
    IsolatedRoot fresh = isolate_roots(RationalPolynomial({mpq_class(-1, 2), 0, 1}), 0, 1)[0];
    EXPECT_EQ(sign_at(RationalPolynomial::linear(-value, 1), fresh), expected) << value;
    EXPECT_EQ(sign_at(RationalPolynomial({-1, 0, 2}), fresh), 0);
  }
}

TEST(RationalPolynomial, RootsJustOutsideOrAtTheEndsOfTheInterval) {
  const mpq_class tiny(1, mpz_class(1) << 70);
  EXPECT_TRUE(isolate_roots(RationalPolynomial::linear(-(1 + tiny), 1), 0, 1).empty());
  EXPECT_TRUE(isolate_roots(RationalPolynomial::linear(tiny, 1), 0, 1).empty());
  EXPECT_EQ(isolate_roots(RationalPolynomial::linear(-tiny, 1), 0, 1).size(), 1u);
  EXPECT_EQ(isolate_roots(RationalPolynomial::linear(-1, 1), 0, 1).size(), 1u);
  // (t - 1/3)^2 + 2^-140 has no real root; (t - 1/3)^2 - 2^-140 two, 2^-70 apart
  const RationalPolynomial square = from_roots({mpq_class(1, 3), mpq_class(1, 3)});
  EXPECT_TRUE(isolate_roots(square + RationalPolynomial({tiny * tiny}), 0, 1).empty());
  EXPECT_EQ(isolate_roots(square - RationalPolynomial({tiny * tiny}), 0, 1).size(), 2u);
}

TEST(RationalPolynomial, MonotoneOnTheIntervalButNotSquareFree) {
  // (t - 1/3)(t - 3)^2: the double root lies outside [0, 1], where f is monotone, so f itself
  // isolates the root (no gcd with f'); signs there stay exact, zeros included.
  const RationalPolynomial f = from_roots({mpq_class(1, 3), 3, 3});
  std::vector<IsolatedRoot> roots = isolate_roots(f, 0, 1);
  ASSERT_EQ(roots.size(), 1u);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(mpq_class(-1, 3), 1), roots[0]), 0);
  EXPECT_EQ(sign_at(from_roots({3, 3}), roots[0]), 1);
  const mpq_class tiny(1, mpz_class(1) << 80);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(mpq_class(-1, 3) - tiny, 1), roots[0]), -1);
  EXPECT_EQ(sign_at(RationalPolynomial::linear(mpq_class(-1, 3) + tiny, 1), roots[0]), 1);
  EXPECT_EQ(isolate_roots(f, 0, 4).size(), 2u);  // the double root once, beside the simple one
}

TEST(RationalPolynomial, BernsteinCoefficientsBoundTheRange) {
  const RationalPolynomial p({1, -3, 2});  // (1 - t)(1 - 2t)
  const std::vector<mpq_class> b = bernstein_coefficients(p, 0, 1);
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0], 1);                 // p(0)
  EXPECT_EQ(b[1], mpq_class(-1, 2));  // 1 + (-3)/2
  EXPECT_EQ(b[2], 0);                 // p(1)
}

TEST(RationalPolynomial, BernsteinSignsAreTheCoefficientsSigns) {
  // Random rational polynomials (degrees 0 to 7, coefficients with denominators) on random
  // rational intervals, negative ends included, and on intervals around a root, where
  // coefficients vanish.
  std::mt19937 rng(29);
  std::uniform_int_distribution<int> numerator(-40, 40), denominator(1, 12), degree(0, 7);
  const auto rational = [&] { return mpq_class(numerator(rng), denominator(rng)); };
  for (int trial = 0; trial < 400; ++trial) {
    std::vector<mpq_class> c(size_t(degree(rng)) + 1);
    for (mpq_class& x : c) {
      x = rational();
      x.canonicalize();
    }
    const RationalPolynomial f(c);
    mpq_class a = rational(), b = rational();
    a.canonicalize();
    b.canonicalize();
    if (trial % 4 == 0) {  // an interval with a root of f at its end
      b = a + 1;
      const RationalPolynomial g = f * RationalPolynomial::linear(-a, 1);
      const std::vector<mpq_class> reference = bernstein_coefficients(g, a, b);
      const std::vector<int> signs = bernstein_signs(g, a, b);
      ASSERT_EQ(signs.size(), reference.size());
      for (std::size_t k = 0; k < signs.size(); ++k) EXPECT_EQ(signs[k], sgn(reference[k]));
      continue;
    }
    if (a == b) continue;
    if (b < a) std::swap(a, b);
    const std::vector<mpq_class> reference = bernstein_coefficients(f, a, b);
    const std::vector<int> signs = bernstein_signs(f, a, b);
    ASSERT_EQ(signs.size(), reference.size()) << trial;
    for (std::size_t k = 0; k < signs.size(); ++k)
      EXPECT_EQ(signs[k], sgn(reference[k])) << "trial " << trial << ", k " << k;
  }
}

}  // namespace
}  // namespace kinray
