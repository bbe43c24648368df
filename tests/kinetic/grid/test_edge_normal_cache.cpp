#include <gtest/gtest.h>

#include <random>

#include "kinetic/grid/coverage_rule.h"
#include "kinetic/grid/edge_normal_cache.h"

namespace kinray {
namespace {

PointMotion random_motion(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-10, 10);
  PointMotion p;
  p.a = Eigen::Vector3d(u(rng), u(rng), u(rng));
  p.b = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return p;
}

void expect_same(const EdgeNormal& x, const EdgeNormal& y) {
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(x.c0[k], y.c0[k]);
    EXPECT_EQ(x.c1[k], y.c1[k]);
    EXPECT_EQ(x.c2[k], y.c2[k]);
  }
}

// The band reads a triangle's edge normal from the cache of the edge in its own direction,
// negated when the triangle runs the other way: that must be bit for bit the normal it built
// from its own vertices, for any motions.
TEST(EdgeNormalCache, ReversedIsTheNormalOfTheOtherDirection) {
  std::mt19937_64 rng(5);
  for (int i = 0; i < 1000; ++i) {
    const PointMotion p = random_motion(rng), q = random_motion(rng);
    expect_same(edge_normal(p, q).reversed(), edge_normal(q, p));
  }
}

TEST(EdgeNormalCache, BuildsOncePerGenerationAndForgetsOnInvalidate) {
  std::mt19937_64 rng(6);
  EdgeNormalCache cache(3);
  const PointMotion p = random_motion(rng), q = random_motion(rng), r = random_motion(rng);
  expect_same(cache.get(1, p, q), edge_normal(p, q));
  // The same generation: the motions are not read again (they have not changed in the band).
  expect_same(cache.get(1, p, r), edge_normal(p, q));
  expect_same(cache.get(2, q, r), edge_normal(q, r));
  cache.invalidate();
  expect_same(cache.get(1, p, r), edge_normal(p, r));
  expect_same(cache.get(2, r, q), edge_normal(r, q));
}

// covers_now takes the sign of a reversed normal from the normal itself (the negation of its
// Horner value); it must be edge_sign of the reversed normal, exact zeros and the zero normal
// (an edge through the eye, + both ways) included. Small integer motions at half-integer pixels
// and dyadic times make exact zeros of the edge function common.
TEST(EdgeNormalCache, ReversedEdgeSignIsTheSignOfTheReversedNormal) {
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<int> small(-2, 2);
  auto integer_motion = [&] {
    PointMotion p;
    p.a = Eigen::Vector3d(small(rng), small(rng), small(rng));
    p.b = Eigen::Vector3d(small(rng), small(rng), small(rng));
    return p;
  };
  int zeros = 0, through_eye = 0;
  for (int i = 0; i < 20000; ++i) {
    const bool integer = i % 2 == 0;
    const PointMotion p = integer ? integer_motion() : random_motion(rng);
    // Every fourth: q on the line through the eye and p (the normal vanishes identically).
    PointMotion q = integer ? integer_motion() : random_motion(rng);
    if (i % 4 == 1) {
      q.a = 2 * p.a;
      q.b = 2 * p.b;
    }
    const EdgeNormal n = edge_normal(p, q);
    const double x = 0.5 * small(rng), y = 0.5 * small(rng), s = 0.25 * (small(rng) + 2);
    const int expected = edge_sign(n.reversed(), x, y, s);
    EXPECT_EQ(reversed_edge_sign(n, x, y, s), expected) << "i = " << i;
    EXPECT_EQ(edge_sign(edge_normal(q, p), x, y, s), expected) << "i = " << i;
    zeros += n.along(x, y)(s) == 0;
    through_eye += n.along(x, y).is_zero() && n.perturbed(x, y).is_zero();
  }
  EXPECT_GT(zeros, 1000);
  EXPECT_GT(through_eye, 100);
}

}  // namespace
}  // namespace kinray
