// The per-segment polynomials of a moving triangle against direct evaluation from positions.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "kinetic/grid/coverage_rule.h"
#include "kinetic/grid/pixel_depth_order.h"
#include "kinetic/grid/row_record.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {
namespace {

using Vec = Eigen::Vector3d;

TriangleMotion random_motion(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2, 2);
  TriangleMotion m;
  for (PointMotion& p : m.v) {
    p.a = Vec(u(rng), u(rng), u(rng));
    p.b = Vec(u(rng), u(rng), u(rng));
  }
  return m;
}

double rel(double value, double scale) { return std::abs(value) / std::max(1.0, std::abs(scale)); }

TEST(TriangleMotion, PolynomialsMatchPositionsAtEveryTime) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const TriangleMotion m = random_motion(rng);
    const double x = u(rng), y = u(rng), s = 2 * u(rng);
    const Vec d(x, y, 1), p0 = m.v[0].at(s), p1 = m.v[1].at(s), p2 = m.v[2].at(s);
    const PixelPolynomials pp = pixel_polynomials(m, x, y);
    EXPECT_LT(rel(pp.edge[0](s) - p0.cross(p1).dot(d), p0.cross(p1).dot(d)), 1e-12);
    EXPECT_LT(rel(pp.edge[1](s) - p1.cross(p2).dot(d), p1.cross(p2).dot(d)), 1e-12);
    EXPECT_LT(rel(pp.edge[2](s) - p2.cross(p0).dot(d), p2.cross(p0).dot(d)), 1e-12);
    const double det = p0.dot(p1.cross(p2));
    EXPECT_LT(rel(pp.orientation(s) - det, det), 1e-11);
    const double denominator = (p1 - p0).cross(p2 - p0).dot(d);
    EXPECT_LT(rel(pp.denominator()(s) - denominator, denominator), 1e-11);
    for (int k = 0; k < 3; ++k)
      EXPECT_NEAR(row_side(m.v[size_t(k)], y)(s), m.v[size_t(k)].at(s).y() - y * m.v[size_t(k)].at(s).z(), 1e-12);
    // The depth polynomials give the plane depth of the ray.
    const DepthPolynomials dp = depth_polynomials(m, x, y);
    const double z = dp.numerator(s) / dp.denominator(s);
    const double z_direct = plane_depth(p0, p1, p2, x, y);
    if (std::abs(z_direct) < 1e6) {
      EXPECT_LT(rel(z - z_direct, z_direct), 1e-8);
    }
  }
}

TEST(TriangleMotion, EdgeNormalIsExactlyAntisymmetricAndZeroOnRepeatedVertices) {
  std::mt19937 rng(3);
  for (int trial = 0; trial < 100; ++trial) {
    const TriangleMotion m = random_motion(rng);
    const EdgeNormal pq = edge_normal(m.v[0], m.v[1]), qp = edge_normal(m.v[1], m.v[0]);
    EXPECT_EQ(pq.c0, -qp.c0);
    EXPECT_EQ(pq.c1, -qp.c1);
    EXPECT_EQ(pq.c2, -qp.c2);
    TriangleMotion degenerate = m;
    degenerate.v[size_t(trial % 3)] = degenerate.v[size_t((trial + 1) % 3)];
    EXPECT_TRUE(degenerate.orientation().is_zero()) << "trial " << trial;
    // A degenerate triangle covers no ray.
    const CoverageRule rule(degenerate, 0.25);
    EXPECT_FALSE(rule.covers(0.1, 0.2));
  }
}

TEST(TriangleMotion, CollinearVerticesHaveZeroOrientationAndNearCollinearOnesTheirExactSign) {
  // The kitchen's sliver at t = 7.18 s: one x and z, three heights. In double O was 6.5e-19.
  TriangleMotion sliver;
  const double y[3] = {-0.38992199646799108, -0.35695226633554455, -0.36024923945868836};
  for (int v = 0; v < 3; ++v) {
    sliver.v[size_t(v)].a = Vec(-1.2248698428063562, y[v], 0.65308772788891489);
    sliver.v[size_t(v)].b = Vec(26.842460395776044, 0, -1.0286719045449793);
  }
  EXPECT_TRUE(sliver.orientation().is_zero());
  EXPECT_FALSE(CoverageRule(sliver, 0.022556944027691372).covers(-0.98333333333333339, -0.58333333333333326));
  // Vertices on a line through two random points, moving along it: collinear at every time.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec p(u(rng), u(rng), u(rng)), q(0x1p-3 * std::round(8 * u(rng)), 0, 0);
    TriangleMotion line;
    for (int v = 0; v < 3; ++v) line.v[size_t(v)].a = p + q * double(v + trial % 4);
    for (int v = 0; v < 3; ++v) line.v[size_t(v)].b = Vec(0.5, -0.25, 0.125) * double(trial % 3);
    EXPECT_TRUE(line.orientation().is_zero()) << "trial " << trial;
  }
  // Lifted off the line by one unit in the last place: O is tiny, and of the exact sign.
  TriangleMotion thin = sliver;
  thin.v[2].a.x() = std::nextafter(thin.v[2].a.x(), 0.0);
  const Vec p0 = thin.v[0].at(0), p1 = thin.v[1].at(0);
  // det at s = 0, by hand: v0 and v1 share x and z, so only v2's x offset h counts.
  const double h = thin.v[2].a.x() - thin.v[0].a.x();
  const double exact_sign = (h * (p0.y() * p1.z() - p1.y() * p0.z())) > 0 ? 1 : -1;
  EXPECT_FALSE(thin.orientation().is_zero());
  EXPECT_EQ(sign_after(thin.orientation(), 0), exact_sign);
}

TEST(TriangleMotion, RebasedMotionIsTheSameMotion) {
  std::mt19937 rng(11);
  const TriangleMotion m = random_motion(rng);
  const TriangleMotion r = m.rebased(0.75);
  for (int k = 0; k < 3; ++k)
    EXPECT_LT((r.v[size_t(k)].at(0.25) - m.v[size_t(k)].at(1.0)).norm(), 1e-14);
}

TEST(CoverageRule, SignRuleAgreesWithRayTriangleIntersection) {
  // The ray (not the line) from the eye pierces the triangle: checked against the explicit
  // intersection for triangles in front of, straddling and behind the eye.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-3, 3), w(-0.8, 0.8);
  int hits = 0, behind_lines = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    TriangleMotion m;
    for (PointMotion& p : m.v) p.a = Vec(u(rng), u(rng), u(rng));
    const double x = w(rng), y = w(rng);
    const Vec d(x, y, 1), p0 = m.v[0].a, p1 = m.v[1].a, p2 = m.v[2].a;
    const double z = plane_depth(p0, p1, p2, x, y);
    const Vec h = z * d;  // the line meets the plane here
    const Vec n = (p1 - p0).cross(p2 - p0);
    const double a0 = (p1 - h).cross(p2 - h).dot(n), a1 = (p2 - h).cross(p0 - h).dot(n),
                 a2 = (p0 - h).cross(p1 - h).dot(n);
    const bool inside = (a0 > 0 && a1 > 0 && a2 > 0) || (a0 < 0 && a1 < 0 && a2 < 0);
    // Skip rays that graze an edge within rounding.
    const double margin = 1e-9 * n.squaredNorm() * (1 + h.squaredNorm());
    if (std::min({std::abs(a0), std::abs(a1), std::abs(a2)}) < margin) continue;
    const bool expected = inside && z > 0;
    behind_lines += inside && z < 0;
    hits += expected;
    EXPECT_EQ(CoverageRule(m, 0).covers(x, y), expected) << "trial " << trial;
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(behind_lines, 100);  // lines that meet the triangle behind the eye are not hits
}

// row_side_sign is sign_plus of row_side: generic motions, and small integer motions at dyadic
// times and rows, where the side vanishes exactly at s (the derivative decides) or for all s
// (the zero polynomial, read as +1).
TEST(CoverageRule, RowSideSignIsThePolynomialsSign) {
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(-10, 10);
  std::uniform_int_distribution<int> small(-2, 2);
  int zeros = 0;
  for (int i = 0; i < 100000; ++i) {
    PointMotion p;
    double s, y;
    if (i % 2 == 0) {
      p.a = Vec(u(rng), u(rng), u(rng));
      p.b = Vec(u(rng), u(rng), u(rng));
      s = u(rng);
      y = u(rng) / 10;
    } else {
      p.a = Vec(small(rng), small(rng), small(rng));
      p.b = Vec(small(rng), small(rng), small(rng));
      s = std::ldexp(double(small(rng)), -1);
      y = std::ldexp(double(small(rng)), -2);
    }
    const Polynomial side = row_side(p, y);
    zeros += side(s) == 0;
    ASSERT_EQ(row_side_sign(p, y, s), sign_plus(side, s)) << "draw " << i;
  }
  EXPECT_GT(zeros, 2000);  // the exact zeros, where the value alone does not decide, are tested
}

TEST(CoverageRule, PerturbedEdgeSignIsThePolynomialsSign) {
  // Small integer normals at dyadic rays and times: many exact zeros of E(d), of n_x and of the
  // Taylor shift's slope, where the written-out signs must take the polynomials' branches.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-10, 10);
  std::uniform_int_distribution<int> small(-1, 1);
  int zero_values = 0, zero_rays = 0;
  for (int i = 0; i < 100000; ++i) {
    EdgeNormal n;
    double x, y, s;
    if (i % 4 == 0) {
      n.c0 = Vec(u(rng), u(rng), u(rng));
      n.c1 = Vec(u(rng), u(rng), u(rng));
      n.c2 = Vec(u(rng), u(rng), u(rng));
      x = u(rng) / 10;
      y = u(rng) / 10;
      s = u(rng);
    } else {
      auto v = [&] { return Vec(small(rng), small(rng), small(rng)); };
      n.c0 = v();
      n.c1 = i % 3 == 0 ? Vec(0, 0, 0) : v();
      n.c2 = i % 5 == 0 ? Vec(0, 0, 0) : v();
      x = std::ldexp(double(small(rng)), -1);
      y = std::ldexp(double(small(rng)), -1);
      s = std::ldexp(double(small(rng)), -1);
    }
    zero_values += n.along(x, y)(s) == 0;
    zero_rays += n.along(x, y).is_zero();
    ASSERT_EQ(perturbed_edge_sign(n, x, y, s), sign_plus(n.perturbed(x, y), s)) << "draw " << i;
    ASSERT_EQ(perturbed_reversed_edge_sign(n, x, y, s), sign_plus(n.reversed().perturbed(x, y), s))
        << "draw " << i;
  }
  EXPECT_GT(zero_values, 5000);
  EXPECT_GT(zero_rays, 1000);
}

TEST(SlotCircle, LocatesAndCrossesOnTheProjectiveCircle) {
  const SlotCircle circle{5};
  EXPECT_EQ(circle.watched(0), (std::pair<int, int>{0, 4}));
  EXPECT_EQ(circle.watched(3), (std::pair<int, int>{2, 3}));
  EXPECT_EQ(circle.across(0, 0), 1);
  EXPECT_EQ(circle.across(1, 0), 0);
  EXPECT_EQ(circle.across(0, 4), 4);
  EXPECT_EQ(circle.across(4, 4), 0);
  EXPECT_EQ(circle.across(2, 2), 3);
  EXPECT_EQ(circle.across(3, 2), 2);
  for (int change = 0; change <= 5; ++change) {
    const int slot = circle.locate([&](int q) { return q < change ? 1 : -1; });
    EXPECT_EQ(slot, change == 0 || change == 5 ? 0 : change);
  }
  const SlotCircle single{1};
  EXPECT_EQ(single.across(0, 0), 0);
  EXPECT_EQ(single.locate([](int) { return -1; }), 0);
}

}  // namespace
}  // namespace kinray
