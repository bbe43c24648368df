// Two triangles sharing an edge: their depth certificate's product difference is kappa times the
// fold volume times the shared edge's function along the ray, so their order is the volume's sign.
#include <gtest/gtest.h>

#include <random>

#include "kinetic/grid/fold_certificate.h"

namespace kinray {
namespace {

TEST(FoldCertificate, FindsTheSharedEdgeAndItsDirection) {
  // a = (p, q, a') = (10, 11, 12); p = a[first], q = a[first + 1].
  const std::array<uint32_t, 3> a{10, 11, 12};
  const auto reversed = shared_edge(a, {11, 10, 13});  // b runs q -> p: a consistent mesh
  ASSERT_TRUE(reversed);
  EXPECT_EQ(reversed->first, 0);
  EXPECT_EQ(reversed->kappa, -1);
  EXPECT_EQ(reversed->b_other, 2);
  const auto rotated = shared_edge(a, {13, 12, 11});  // edge 11 -> 12 of a, reversed in b
  ASSERT_TRUE(rotated);
  EXPECT_EQ(rotated->first, 1);
  EXPECT_EQ(rotated->kappa, -1);
  EXPECT_EQ(rotated->b_other, 0);
  const auto same = shared_edge(a, {12, 10, 13});  // b runs 12 -> 10 like a's edge 12 -> 10
  ASSERT_TRUE(same);
  EXPECT_EQ(same->first, 2);
  EXPECT_EQ(same->kappa, 1);
  EXPECT_EQ(same->b_other, 2);
  EXPECT_FALSE(shared_edge(a, {10, 13, 14}));  // one vertex only
  EXPECT_FALSE(shared_edge(a, {13, 14, 15}));
}

PointMotion random_motion(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  PointMotion m;
  m.a = Eigen::Vector3d(u(rng), u(rng), 3 + u(rng));
  m.b = Eigen::Vector3d(u(rng), u(rng), u(rng));
  return m;
}

TEST(FoldCertificate, ProductDifferenceIsKappaTimesVolumeTimesEdgeFunction) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  for (int trial = 0; trial < 2000; ++trial) {
    const PointMotion p = random_motion(rng), q = random_motion(rng), a = random_motion(rng),
                      b = random_motion(rng);
    const double x = u(rng), y = u(rng);
    const bool reversed = trial % 2 == 0;
    const TriangleMotion ta{{p, q, a}};
    const TriangleMotion tb = reversed ? TriangleMotion{{q, p, b}} : TriangleMotion{{p, q, b}};
    const DepthPolynomials da = depth_polynomials(ta, x, y), db = depth_polynomials(tb, x, y);
    const Polynomial f = db.numerator * da.denominator - da.numerator * db.denominator;
    const Polynomial product = fold_volume(p, q, a, b) * edge_normal(p, q).along(x, y);
    const double kappa = reversed ? -1 : 1;
    for (double s : {0.0, 0.3, 0.7, 1.0}) {
      double scale = 0;
      for (int k = 0; k <= 5; ++k) scale += std::abs(f.c[size_t(k)]) * std::pow(s, k);
      EXPECT_NEAR(f(s), kappa * product(s), 1e-12 * (1 + scale)) << "trial " << trial;
    }
  }
}

}  // namespace
}  // namespace kinray
