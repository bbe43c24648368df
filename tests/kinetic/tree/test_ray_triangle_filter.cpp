// The float rejection ahead of the exact ray-triangle test never rejects a triangle the exact
// test hits (rays through edges and vertices included), and rejects most clear misses.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>

#include "kinetic/tree/ray_triangle.h"
#include "kinetic/tree/ray_triangle_filter.h"

namespace kinray {
namespace {

struct Points {
  alignas(16) float p[3][4];
};

/// The nearest floats of the positions, after moving each coordinate by up to a few double ulps
/// (the kinetic trees round a + b (t - o), the exact test reads the key blend).
Points points_of(const std::array<Eigen::Vector3d, 3>& exact, std::mt19937& rng) {
  std::uniform_int_distribution<int> ulps(-4, 4);
  Points q;
  for (int c = 0; c < 3; ++c) {
    for (int a = 0; a < 3; ++a) {
      double x = exact[size_t(c)][a];
      for (int k = ulps(rng); k != 0; k += k > 0 ? -1 : 1)
        x = std::nextafter(x, k > 0 ? INFINITY : -INFINITY);
      q.p[c][a] = float(x);
    }
    q.p[c][3] = 0;
  }
  return q;
}

Eigen::Vector3d random_unit(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Vector3d(n(rng), n(rng), n(rng)).normalized();
}

TEST(RayTriangleFilter, NeverRejectsAHitAndRejectsMostClearMisses) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> uniform(0, 1), log_scale(-3, 3);
  int hits = 0, boundary_hits = 0, clear_misses = 0, clear_rejected = 0;
  for (int trial = 0; trial < 200000; ++trial) {
    // A triangle 10^[-3, -1] of its distance from the origin in size (camera-space triangles:
    // a hundredth of a unit at a few units), at 10^[-3, 3]: floats place it to 2^-24 of the
    // distance, a thousandth of its size at most.
    const double far = std::pow(10.0, log_scale(rng));
    const double size = far * std::pow(10.0, log_scale(rng) / 3 - 2);
    const Eigen::Vector3d centre = far * random_unit(rng);
    std::array<Eigen::Vector3d, 3> p;
    for (Eigen::Vector3d& v : p) v = centre + size * random_unit(rng);
    // Rays through a point of the triangle's plane: inside, on an edge, at a vertex, or outside
    // by a random barycentric amount (near and far).
    double u = uniform(rng), v = uniform(rng) * (1 - u);
    const int kind = trial % 6;  // 0: on the edge p0 p1, 1: on the edge p1 p2, 2: at p0,
                                 // 3: just outside (or far), 4: outside, 5: inside
    if (kind == 0) v = 0;
    if (kind == 1) v = 1 - u;
    if (kind == 2) u = v = 0;
    if (kind == 3) u = -std::pow(10.0, -6 * uniform(rng));
    if (kind == 4) u += 1 + 2 * uniform(rng);
    const Eigen::Vector3d target = p[0] + u * (p[1] - p[0]) + v * (p[2] - p[0]);
    const Eigen::Vector3d direction = std::pow(10.0, log_scale(rng)) * random_unit(rng);
    const Eigen::Vector3d origin = target - (0.5 + uniform(rng)) * direction;
    const Points q = points_of(p, rng);
    const double scale = std::max(
        {p[0].cwiseAbs().maxCoeff(), p[1].cwiseAbs().maxCoeff(), p[2].cwiseAbs().maxCoeff()});
    const bool rejects =
        RayTriangleFilter(origin, direction, scale, 0).misses(q.p[0], q.p[1], q.p[2]);
    const bool hit = ray_triangle(origin, direction, p[0], p[1], p[2]).has_value();
    if (hit) {
      ++hits;
      boundary_hits += kind < 3;
      ASSERT_FALSE(rejects) << "trial " << trial << ": a hit rejected";
      continue;
    }
    if (kind == 4) {  // outside by a barycentric 1 or more
      ++clear_misses;
      clear_rejected += rejects;
    }
  }
  EXPECT_GT(hits, 50000);
  EXPECT_GT(boundary_hits, 20000);  // rays through edges and vertices that the exact test hits
  EXPECT_GT(clear_misses, 30000);
  EXPECT_GT(clear_rejected, clear_misses * 99 / 100);
}

TEST(RayTriangleFilter, RejectsNothingBeyondTheFloatRangeOrWithoutADirection) {
  const Eigen::Vector3d origin(0, 0, -1);
  const Points far{{{INFINITY, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}}};
  EXPECT_FALSE(RayTriangleFilter(origin, Eigen::Vector3d(5, 5, 1), INFINITY, 0)
                   .misses(far.p[0], far.p[1], far.p[2]));
  const Points nan{{{NAN, 0, 0, 0}, {0, 1, 0, 0}, {1, 1, 0, 0}}};
  EXPECT_FALSE(RayTriangleFilter(origin, Eigen::Vector3d(5, 5, 1), 1, 0)
                   .misses(nan.p[0], nan.p[1], nan.p[2]));
  const Points unit{{{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 1, 0, 0}}};
  EXPECT_FALSE(RayTriangleFilter(origin, Eigen::Vector3d::Zero(), 1, 0)
                   .misses(unit.p[0], unit.p[1], unit.p[2]));
  // The same triangle, a ray passing far beside it: rejected.
  EXPECT_TRUE(RayTriangleFilter(origin, Eigen::Vector3d(5, 5, 1), 1, 0)
                  .misses(unit.p[0], unit.p[1], unit.p[2]));
}

}  // namespace
}  // namespace kinray
