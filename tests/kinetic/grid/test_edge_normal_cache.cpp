#include <gtest/gtest.h>

#include <random>

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

}  // namespace
}  // namespace kinray
