// Bernstein enclosures (bernstein_bound.h) against exact rational arithmetic: after any path of
// halvings, the exact polynomial's values on the piece lie in the enclosure, and its values at
// the piece's ends within the slack of the end coefficients.
#include <gmpxx.h>
#include <gtest/gtest.h>

#include <random>

#include "kinetic/collision/bernstein_bound.h"

namespace kinray::detail {
namespace {

/// The exact value at s in [0, 1] of the polynomial with Bernstein coefficients b (de Casteljau).
mpq_class exact_value(std::vector<mpq_class> b, const mpq_class& s) {
  for (std::size_t level = 1; level < b.size(); ++level)
    for (std::size_t k = 0; k + level < b.size(); ++k) b[k] = (1 - s) * b[k] + s * b[k + 1];
  return b[0];
}

TEST(BernsteinBound, HalvingsEncloseTheExactPolynomial) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coefficient(-1, 1);
  std::uniform_int_distribution<int> side(0, 1);
  int near_misses = 0;
  for (int trial = 0; trial < 500; ++trial) {
    std::array<Interval, 5> exact_coefficients;
    std::vector<mpq_class> b;
    for (Interval& c : exact_coefficients) {
      c = Interval::point(coefficient(rng) * std::ldexp(1.0, int(trial % 7) - 3));
      b.emplace_back(c.lo);
    }
    BernsteinBound<4> piece = BernsteinBound<4>::enclosing(exact_coefficients);
    mpq_class lo = 0, width = 1;  // the piece [lo, lo + width] of [0, 1]
    for (int depth = 0; depth < 12; ++depth) {
      auto [left, right] = piece.halves();
      width /= 2;
      if (side(rng) == 1) {
        lo += width;
        piece = right;
      } else {
        piece = left;
      }
      const mpq_class hi = lo + width;
      for (const mpq_class* end : std::array<const mpq_class*, 2>{&lo, &hi}) {
        const mpq_class value = exact_value(b, *end);
        const double at = end == &lo ? piece.c[0] : piece.c[4];
        EXPECT_LE(abs(value - at), mpq_class(piece.slack)) << "trial " << trial;
        near_misses += value != at;
      }
      const mpq_class inside = exact_value(b, lo + width / 3);
      EXPECT_GE(inside, *std::min_element(piece.c.begin(), piece.c.end()) - piece.slack);
      EXPECT_LE(inside, *std::max_element(piece.c.begin(), piece.c.end()) + piece.slack);
    }
  }
  EXPECT_GT(near_misses, 0);  // the averages do round: the slack is what holds them
}

TEST(BernsteinBound, MonotoneOnlyWhenTheExactDerivativeKeepsItsSign) {
  // t^2 - 1/4 on [0, 1]: Bernstein (-1/4, -1/4, 3/4); not monotone on [0, 1] by its
  // coefficients (a flat first difference), monotone on the right half
  const BernsteinBound<2> whole = BernsteinBound<2>::enclosing(
      {Interval::point(-0.25), Interval::point(-0.25), Interval::point(0.75)});
  EXPECT_FALSE(whole.certainly_monotone());
  EXPECT_TRUE(whole.halves().second.certainly_monotone());
  EXPECT_EQ(whole.start_sign(), -1);
  EXPECT_EQ(whole.end_sign(), 1);
}

}  // namespace
}  // namespace kinray::detail
