// The pair arithmetic against the scalar code, bit for bit: blend_pair against
// FlightplanMesh::position, triangle_plane_pair against TrianglePlane, plane_depth_pair against
// TrianglePlane::depth; random triangles of every scale, rays across and beyond the image, and
// the degenerate cases (the eye in the plane, a plane through the ray's direction, zero-area
// triangles, subnormal and huge coordinates).
#include "kinetic/grid/plane_pairs.h"

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "kinetic/grid/grid_input.h"

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

void expect_same_plane(const TrianglePlane& pair, const TrianglePlane& scalar) {
  EXPECT_TRUE(same(pair.numerator, scalar.numerator)) << pair.numerator << " vs " << scalar.numerator;
  for (int c = 0; c < 3; ++c)
    EXPECT_TRUE(same(pair.normal[c], scalar.normal[c])) << c << ": " << pair.normal[c] << " vs " << scalar.normal[c];
}

TEST(PlanePairs, BlendMatchesGridMeshPosition) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-8, 8), time(0.0, 3.0);
  std::vector<Eigen::Vector3d> positions;  // two vertices at four keys
  for (int k = 0; k < 8; ++k)
    positions.emplace_back(unit(rng) * std::pow(10.0, exponent(rng)), unit(rng), unit(rng) * 1e3);
  const std::vector<double> key_times = {0.0, 0.7, 1.9, 3.0};
  FlightplanMesh mesh;
  mesh.key_times = key_times;
  mesh.positions = positions;
  mesh.vertex_count = 2;
  for (int trial = 0; trial < 2000; ++trial) {
    const FlightplanMesh::KeyBlend b0 = mesh.blend_at(time(rng)), b1 = mesh.blend_at(time(rng));
    ASSERT_FALSE(b0.still || b1.still);
    const PointPair blended =
        blend_pair(point_pair(mesh.key_position(b0.k, 0), mesh.key_position(b1.k, 1)),
                   point_pair(mesh.key_position(b0.k + 1, 0), mesh.key_position(b1.k + 1, 1)),
                   DoublePair{b0.alpha, b1.alpha});
    const Eigen::Vector3d p0 = mesh.position(0, b0), p1 = mesh.position(1, b1);
    for (int c = 0; c < 3; ++c) {
      const DoublePair& lane = c == 0 ? blended.x : c == 1 ? blended.y : blended.z;
      EXPECT_TRUE(same(lane[0], p0[c]));
      EXPECT_TRUE(same(lane[1], p1[c]));
    }
  }
}

TEST(PlanePairs, TrianglePlanesMatchTrianglePlane) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> unit(-1, 1), exponent(-12, 12);
  auto point = [&] {
    const double scale = std::pow(10.0, exponent(rng));
    return Vec(unit(rng) * scale, unit(rng) * scale, unit(rng) * scale);
  };
  const double tiny = std::numeric_limits<double>::denorm_min();
  std::vector<std::array<Vec, 3>> triangles = {
      {Vec(0, 0, 0), Vec(1, 0, 1), Vec(0, 1, 1)},
      {Vec(0, 0, 1), Vec(1, 1, 2), Vec(2, 2, 3)},
      {Vec(tiny, 0, 1), Vec(0, tiny, 1), Vec(tiny, tiny, 1)},
      {Vec(1e300, 0, 1), Vec(0, 1e300, 1), Vec(-1e300, -1e300, 1)},
      {Vec(-0.0, 0.0, -0.0), Vec(0.0, -0.0, 1), Vec(1, 0.0, -0.0)},
  };
  for (int k = 0; k < 20000; ++k) triangles.push_back({point(), point(), point()});
  for (size_t k = 0; k + 1 < triangles.size(); ++k) {
    const auto& a = triangles[k];
    const auto& b = triangles[k + 1];
    TrianglePlane first(Vec::Zero(), Vec::Zero(), Vec::Zero()), second = first;
    triangle_plane_pair(point_pair(a[0], b[0]), point_pair(a[1], b[1]), point_pair(a[2], b[2]), first, second);
    expect_same_plane(first, TrianglePlane(a[0], a[1], a[2]));
    expect_same_plane(second, TrianglePlane(b[0], b[1], b[2]));
  }
}

TEST(PlanePairs, DepthMatchesTrianglePlaneOnRandomPlanes) {
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

TEST(PlanePairs, DepthMatchesTrianglePlaneOnDegenerateCases) {
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
