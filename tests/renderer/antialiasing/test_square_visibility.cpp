// The pixel square's visibility (renderer/antialiasing/square_visibility.h): exact areas where
// geometry gives them (a pair crossing at the square's middle, a duplicate, an occluder covering
// the square), and random sets of triangles (crossing pairs, triangles straddling the eye plane or
// behind it) whose visible areas tile the square and match a dense point sampling.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "renderer/antialiasing/exact_pixel.h"
#include "renderer/antialiasing/square_visibility.h"

namespace kinray {
namespace {

/// The camera-space point seen at image position (x, y) at depth z (behind the eye for z < 0,
/// where it still projects to (x, y)).
Vec3 at(double x, double y, double z) {
  return {x * z, y * z, z};
}

/// The nearest triangle pierced by the ray (x, y, 1) by Moller-Trumbore in 3D (not by the
/// half-planes under test), or -1.
int nearest_hit(const std::vector<std::array<Vec3, 3>>& triangles, double x, double y) {
  const Vec3 d(x, y, 1);
  int best = -1;
  double best_t = kInfinity;
  for (size_t k = 0; k < triangles.size(); ++k) {
    const auto& [p0, p1, p2] = triangles[k];
    const Vec3 e1 = p1 - p0, e2 = p2 - p0, pvec = d.cross(e2);
    const double det = e1.dot(pvec);
    if (det == 0) continue;
    const Vec3 tvec = -p0;
    const double u = tvec.dot(pvec) / det;
    const Vec3 qvec = tvec.cross(e1);
    const double v = d.dot(qvec) / det, t = e2.dot(qvec) / det;
    if (u < 0 || v < 0 || u + v > 1 || t <= 0) continue;
    if (t < best_t) {
      best_t = t;
      best = int(k);
    }
  }
  return best;
}

std::vector<ImageTriangle> image_triangles(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::vector<ImageTriangle> out;
  for (const auto& [p0, p1, p2] : triangles) out.push_back(image_triangle(p0, p1, p2));
  return out;
}

TEST(SquareVisibility, PixelSquaresTileTheImage) {
  const PixelRays image{7, 5};
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 7; ++i) {
      const PixelSquare s = pixel_square(image, i, j);
      EXPECT_NEAR((s.x0 + s.x1) / 2, image.x(i), 1e-15);
      EXPECT_NEAR((s.y0 + s.y1) / 2, image.y(j), 1e-15);
      if (i > 0) EXPECT_EQ(s.x0, pixel_square(image, i - 1, j).x1);
      if (j > 0) EXPECT_EQ(s.y1, pixel_square(image, i, j - 1).y0);
    }
}

// A at depth 2 everywhere; B in the plane 1 / z = 1/2 + x / 25, nearer exactly where x > 0: each
// sees half the square, split along x = 0.
TEST(SquareVisibility, CrossingPairSplitsAlongEqualDepth) {
  auto z_b = [](double x) { return 1.0 / (0.5 + x / 25); };
  const std::vector<std::array<Vec3, 3>> triangles = {
      {at(-10, -10, 2), at(10, -10, 2), at(0, 10, 2)},
      {at(-10, -10, z_b(-10)), at(10, -10, z_b(10)), at(0, 10, z_b(0))}};
  const PixelSquare square{-0.1, 0.1, -0.05, 0.15};
  SquareVisibility visibility;
  visibility.resolve(square, image_triangles(triangles));
  EXPECT_NEAR(visibility.visible_area(0), square.area() / 2, 1e-15);
  EXPECT_NEAR(visibility.visible_area(1), square.area() / 2, 1e-15);
  EXPECT_NEAR(visibility.background_area(), 0, 1e-15);
  for (const VisiblePiece& piece : visibility.pieces())
    for (const Vec2& v : visibility.vertices(piece))
      EXPECT_TRUE(piece.owner == 0 ? v.x() <= 1e-15 : v.x() >= -1e-15);
}

TEST(SquareVisibility, NearestCoveringTriangleIsTheFastPath) {
  const std::vector<std::array<Vec3, 3>> triangles = {
      {at(-0.3, -0.3, 5), at(0.3, -0.3, 5), at(0, 0.3, 5)},    // behind, partly in the square
      {at(-10, -10, 1), at(10, -10, 1), at(0, 10, 1)},         // in front, covers it
      {at(0.05, 0.0, 3), at(0.3, 0.0, 3), at(0.05, 0.3, 3)}};  // behind
  const PixelSquare square{-0.1, 0.1, -0.1, 0.1};
  SquareVisibility visibility;
  visibility.resolve(square, image_triangles(triangles));
  EXPECT_TRUE(visibility.covered_by_one());
  ASSERT_EQ(visibility.pieces().size(), 1u);
  EXPECT_EQ(visibility.pieces()[0].owner, 1u);
  EXPECT_DOUBLE_EQ(visibility.visible_area(1), square.area());
}

TEST(SquareVisibility, DuplicateTriangleIsSeenOnce) {
  const std::array<Vec3, 3> t = {at(-1, -1, 2), at(1, -1, 3), at(0, 1, 2.5)};
  const PixelSquare square{-0.1, 0.1, -0.1, 0.1};
  SquareVisibility visibility;
  visibility.resolve(square, image_triangles({t, t}));
  EXPECT_DOUBLE_EQ(visibility.visible_area(0), square.area());
  EXPECT_EQ(visibility.visible_area(1), 0);
}

TEST(SquareVisibility, TriangleBehindTheEyeIsNeverSeen) {
  const std::vector<std::array<Vec3, 3>> triangles = {
      {at(-10, -10, -2), at(10, -10, -2), at(0, 10, -2)}};
  const PixelSquare square{-0.1, 0.1, -0.1, 0.1};
  SquareVisibility visibility;
  visibility.resolve(square, image_triangles(triangles));
  EXPECT_TRUE(visibility.pieces().empty());
  EXPECT_DOUBLE_EQ(visibility.background_area(), square.area());
  EXPECT_EQ(covered_area(square, image_triangles(triangles)[0]), 0);
}

/// A random triangle near `square`: its vertices' image positions within a few squares of it,
/// their depths in [0.5, 4], or, when `straddle`, one or two vertices behind the eye.
std::array<Vec3, 3> random_triangle(const PixelSquare& s, std::mt19937& rng, bool straddle) {
  const double w = s.x1 - s.x0;
  std::uniform_real_distribution<double> x(s.x0 - 1.5 * w, s.x1 + 1.5 * w),
      y(s.y0 - 1.5 * w, s.y1 + 1.5 * w), z(0.5, 4), behind(-3, -0.2);
  std::array<Vec3, 3> t;
  const int back = straddle ? 1 + int(rng() % 2) : 0;
  for (int k = 0; k < 3; ++k) t[size_t(k)] = at(x(rng), y(rng), k < back ? behind(rng) : z(rng));
  return t;
}

// Random sets of 2 to 8 triangles over a square: the visible areas and the background sum to the
// square, and each triangle's visible area matches the share of a 512 x 512 grid of points whose
// nearest hit it is. A point is misclassified only within half a grid step of a boundary and
// those errors mostly cancel along a line: the tolerance, 2e-3 of the square, is about ten times
// the largest error seen, the mean error is asserted below 2e-4.
TEST(SquareVisibility, RandomSetsMatchDenseSampling) {
  constexpr int kGrid = 512;
  std::mt19937 rng(2026);
  const PixelRays image{32, 24};
  SquareVisibility visibility;
  double error_sum = 0;
  int error_count = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const PixelSquare square = pixel_square(image, int(rng() % 32), int(rng() % 24));
    std::vector<std::array<Vec3, 3>> triangles;
    const int n = 2 + int(rng() % 7);
    for (int k = 0; k < n; ++k) triangles.push_back(random_triangle(square, rng, rng() % 4 == 0));
    // An interpenetrating pair: a copy of the first with one vertex pushed through it.
    std::array<Vec3, 3> crossing = triangles[0];
    crossing[1] *= 1.4;
    crossing[2] *= 0.7;
    triangles.push_back(crossing);
    visibility.resolve(square, image_triangles(triangles));

    double sum = visibility.background_area();
    for (size_t k = 0; k < triangles.size(); ++k) sum += visibility.visible_area(uint32_t(k));
    ASSERT_NEAR(sum, square.area(), 1e-12 * square.area()) << "trial " << trial;

    std::vector<int> counts(triangles.size() + 1, 0);
    const double step_x = (square.x1 - square.x0) / kGrid, step_y = (square.y1 - square.y0) / kGrid;
    for (int b = 0; b < kGrid; ++b)
      for (int a = 0; a < kGrid; ++a)
        ++counts[size_t(
            nearest_hit(triangles, square.x0 + (a + 0.5) * step_x, square.y0 + (b + 0.5) * step_y) +
            1)];
    const double cell = square.area() / (double(kGrid) * kGrid);
    EXPECT_NEAR(visibility.background_area(), counts[0] * cell, 2e-3 * square.area())
        << "trial " << trial;
    for (size_t k = 0; k < triangles.size(); ++k) {
      const double error = visibility.visible_area(uint32_t(k)) - counts[k + 1] * cell;
      EXPECT_LT(std::abs(error), 2e-3 * square.area()) << "trial " << trial << " triangle " << k;
      error_sum += std::abs(error) / square.area();
      ++error_count;
    }
  }
  EXPECT_LT(error_sum / error_count, 2e-4);
}

// Many triangles over one square (20 to 30): the pieces still tile it and match the sampling.
TEST(SquareVisibility, CrowdedSquaresMatchDenseSampling) {
  constexpr int kGrid = 256;
  std::mt19937 rng(77);
  const PixelSquare square{0.1, 0.2, -0.3, -0.2};
  SquareVisibility visibility;
  for (int trial = 0; trial < 4; ++trial) {
    std::vector<std::array<Vec3, 3>> triangles;
    const int n = 20 + int(rng() % 11);
    for (int k = 0; k < n; ++k) triangles.push_back(random_triangle(square, rng, rng() % 5 == 0));
    visibility.resolve(square, image_triangles(triangles));
    double sum = visibility.background_area();
    for (size_t k = 0; k < triangles.size(); ++k) sum += visibility.visible_area(uint32_t(k));
    ASSERT_NEAR(sum, square.area(), 1e-12 * square.area()) << "trial " << trial;
    std::vector<int> counts(triangles.size() + 1, 0);
    const double step = (square.x1 - square.x0) / kGrid;
    for (int b = 0; b < kGrid; ++b)
      for (int a = 0; a < kGrid; ++a)
        ++counts[size_t(
            nearest_hit(triangles, square.x0 + (a + 0.5) * step, square.y0 + (b + 0.5) * step) +
            1)];
    const double cell = square.area() / (double(kGrid) * kGrid);
    for (size_t k = 0; k < triangles.size(); ++k)
      EXPECT_NEAR(visibility.visible_area(uint32_t(k)), counts[k + 1] * cell, 4e-3 * square.area())
          << "trial " << trial << " triangle " << k;
  }
}

// A mesh patch: a 4 x 4 grid of quads on a tilted plane, vertices jittered within the plane and
// shared between neighbours, over the square. Nothing hides anything, so each triangle's visible
// area is its covered area, shared edges neither lose nor count twice, and the background is empty.
TEST(SquareVisibility, MeshPatchSharedEdgesTileTheSquare) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  const PixelSquare square{-0.05, 0.05, -0.05, 0.05};
  auto on_plane = [](double x, double y) { return at(x, y, 1.0 / (0.5 + 0.3 * x - 0.2 * y)); };
  std::vector<Vec2> grid;
  for (int b = 0; b <= 4; ++b)
    for (int a = 0; a <= 4; ++a) {
      const bool border = a == 0 || a == 4 || b == 0 || b == 4;
      grid.emplace_back(-0.08 + 0.04 * a + (border ? 0 : jitter(rng)),
                        -0.08 + 0.04 * b + (border ? 0 : jitter(rng)));
    }
  std::vector<std::array<Vec3, 3>> triangles;
  auto vertex = [&](int a, int b) {
    return on_plane(grid[size_t(b * 5 + a)].x(), grid[size_t(b * 5 + a)].y());
  };
  for (int b = 0; b < 4; ++b)
    for (int a = 0; a < 4; ++a) {
      triangles.push_back({vertex(a, b), vertex(a + 1, b), vertex(a + 1, b + 1)});
      triangles.push_back({vertex(a, b), vertex(a + 1, b + 1), vertex(a, b + 1)});
    }
  const std::vector<ImageTriangle> image = image_triangles(triangles);
  SquareVisibility visibility;
  visibility.resolve(square, image);
  EXPECT_NEAR(visibility.background_area(), 0, 1e-12 * square.area());
  for (size_t k = 0; k < triangles.size(); ++k)
    EXPECT_NEAR(visibility.visible_area(uint32_t(k)), covered_area(square, image[k]),
                1e-12 * square.area());
}

// The 7-point rule integrates every monomial x^a y^b of degree <= 5 exactly on a triangle, and
// not all of degree 6; the 3-point rule (small fan triangles) every one of degree <= 2, and not
// all of degree 3.
template <size_t N>
void expect_rule_degree(std::span<const TriangleQuadratureNode, N> rule, int exact_degree) {
  auto integral = [](int a, int b) {  // over the unit right triangle: a! b! / (a + b + 2)!
    auto factorial = [](int n) { return std::tgamma(n + 1.0); };
    return factorial(a) * factorial(b) / factorial(a + b + 2);
  };
  double worst_above = 0;
  for (int degree = 0; degree <= exact_degree + 1; ++degree)
    for (int a = 0; a <= degree; ++a) {
      const int b = degree - a;
      double sum = 0;
      for (const TriangleQuadratureNode& node : rule)
        sum += 0.5 * node.weight * std::pow(node.l1, a) * std::pow(node.l2, b);
      if (degree <= exact_degree)
        EXPECT_NEAR(sum, integral(a, b), 1e-15) << a << " " << b;
      else
        worst_above = std::max(worst_above, std::abs(sum - integral(a, b)));
    }
  EXPECT_GT(worst_above, 1e-6);
}

TEST(ExactPixel, QuadratureRulesHaveDegreesFiveAndTwo) {
  expect_rule_degree(degree5_triangle_rule(), 5);
  expect_rule_degree(degree2_triangle_rule(), 2);
}

}  // namespace
}  // namespace kinray
