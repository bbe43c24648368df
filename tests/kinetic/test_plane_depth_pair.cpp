// plane_depth_pair against TrianglePlane::depth, bit for bit: random triangles of every scale,
// rays across and beyond the image, and the degenerate cases (the eye in the plane, a plane
// through the ray's direction, zero-area triangles, subnormal and huge coordinates).
#include "kinetic/plane_depth_pair.h"

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

namespace kinray {
namespace {

using Vec = Eigen::Vector3d;

// Same bits, or both NaN (a NaN depth is never written: the read-out treats it as a miss).
bool same(double a, double b) {
  return std::bit_cast<uint64_t>(a) == std::bit_cast<uint64_t>(b) || (std::isnan(a) && std::isnan(b));
}

void expect_pair_matches(const TrianglePlane& a, const TrianglePlane& b, double x0, double x1, double y) {
  const DoublePair z = plane_depth_pair(a, b, DoublePair{x0, x1}, y);
  const double za = a.depth(x0, y), zb = b.depth(x1, y);
  EXPECT_TRUE(same(z[0], za)) << z[0] << " vs " << za << " at x " << x0 << " y " << y;
  EXPECT_TRUE(same(z[1], zb)) << z[1] << " vs " << zb << " at x " << x1 << " y " << y;
  EXPECT_TRUE(same(double(float(z[0])), double(float(za))));
}

TEST(PlaneDepthPair, MatchesTrianglePlaneOnRandomPlanes) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-12, 12), image(-2, 2);
  auto coordinate = [&] { return unit(rng) * std::pow(10.0, exponent(rng)); };
  auto point = [&] { return Vec(coordinate(), coordinate(), coordinate()); };
  std::vector<TrianglePlane> planes;
  for (int k = 0; k < 4000; ++k) planes.emplace_back(point(), point(), point());
  // Triangles in front of the camera at ordinary scales, as the scenes make them.
  std::uniform_real_distribution<double> depth(0.1, 100);
  for (int k = 0; k < 4000; ++k) {
    auto at = [&] { const double z = depth(rng); return Vec(image(rng) * z, image(rng) * z, z); };
    planes.emplace_back(at(), at(), at());
  }
  for (size_t k = 0; k + 1 < planes.size(); ++k)
    for (int ray = 0; ray < 25; ++ray)
      expect_pair_matches(planes[k], planes[k + 1], image(rng), image(rng), image(rng));
}

TEST(PlaneDepthPair, MatchesTrianglePlaneOnDegenerateCases) {
  const double tiny = std::numeric_limits<double>::denorm_min(), huge = 1e300;
  const std::vector<TrianglePlane> planes = {
      {Vec(0, 0, 0), Vec(1, 0, 1), Vec(0, 1, 1)},             // the eye is a vertex: numerator 0
      {Vec(1, 0, 1), Vec(2, 0, 2), Vec(0, 1, 1)},             // the eye in the plane
      {Vec(-1, 0, 1), Vec(1, 0, 1), Vec(0, 0, 2)},            // plane y = 0: rays along it
      {Vec(0, 0, 1), Vec(1, 1, 2), Vec(2, 2, 3)},             // zero area: normal 0
      {Vec(0, 0, 1), Vec(0, 0, 1), Vec(0, 0, 1)},             // a point
      {Vec(tiny, 0, 1), Vec(0, tiny, 1), Vec(tiny, tiny, 1)}, // subnormal extent
      {Vec(huge, 0, 1), Vec(0, huge, 1), Vec(-huge, -huge, 1)},
      {Vec(0, 0, -1), Vec(1, 0, -1), Vec(0, 1, -1)},          // behind the eye
      {Vec(1e-9, 0, 1e-9), Vec(0, 1e-9, 1e-9), Vec(0, 0, 2e-9)},
  };
  const std::vector<double> coordinates = {0.0, -0.0, 1.0, -1.0, 0.5, 1e-300, tiny, 3.0, -2.5};
  for (const TrianglePlane& a : planes)
    for (const TrianglePlane& b : planes)
      for (double x : coordinates)
        for (double y : coordinates) expect_pair_matches(a, b, x, -x, y);
}

}  // namespace
}  // namespace kinray
