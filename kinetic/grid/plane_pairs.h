#pragma once
// The read-out's arithmetic two at a time, in the two lanes of a SIMD register: the planes of two
// triangles (FlightplanMesh::position's blend, then TrianglePlane's products) and the depths of two
// pixels (TrianglePlane::depth). Lane for lane the operations are exactly those of the scalar
// code, in the same order -- Eigen's cross product is (a.y b.z - a.z b.y, a.z b.x - a.x b.z,
// a.x b.y - a.y b.x), its 3-vector dot product sums (a.x b.x + a.y b.y) + a.z b.z, and the last
// product of TrianglePlane::depth's dot with (x, y, 1) is exact -- and IEEE arithmetic rounds a
// lane as it rounds a scalar, so every result is the same bit for bit
// (tests/kinetic/grid/test_plane_pairs.cpp checks this against the scalar code).
#include <Eigen/Core>

#include "kinetic/motion/triangle_motion.h"

namespace kinray {

/// Two doubles in one SIMD register (GCC/Clang vector extension: IEEE operations lane by lane).
using DoublePair = double __attribute__((vector_size(16)));

/// Two points, coordinate by coordinate: lane 0 is one point, lane 1 the other.
struct PointPair {
  DoublePair x, y, z;
};

[[nodiscard]] inline PointPair point_pair(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {DoublePair{a.x(), b.x()}, DoublePair{a.y(), b.y()}, DoublePair{a.z(), b.z()}};
}

/// FlightplanMesh::position between two keys, a + alpha (c - a), lane by lane (not for a still
/// blend, which returns a unchanged).
[[nodiscard]] inline PointPair blend_pair(const PointPair& a, const PointPair& c, DoublePair alpha) {
  return {a.x + alpha * (c.x - a.x), a.y + alpha * (c.y - a.y), a.z + alpha * (c.z - a.z)};
}

/// TrianglePlane(p0, p1, p2) of the triangle in each lane, into `first` (lane 0) and `second`.
inline void triangle_plane_pair(const PointPair& p0, const PointPair& p1, const PointPair& p2,
                                TrianglePlane& first, TrianglePlane& second) {
  auto cross = [](const PointPair& a, const PointPair& b) {
    return PointPair{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  };
  auto minus = [](const PointPair& a, const PointPair& b) {
    return PointPair{a.x - b.x, a.y - b.y, a.z - b.z};
  };
  const PointPair c = cross(p1, p2);
  const DoublePair numerator = (p0.x * c.x + p0.y * c.y) + p0.z * c.z;
  const PointPair normal = cross(minus(p1, p0), minus(p2, p0));
  first.numerator = numerator[0];
  first.normal = Eigen::Vector3d(normal.x[0], normal.y[0], normal.z[0]);
  second.numerator = numerator[1];
  second.normal = Eigen::Vector3d(normal.x[1], normal.y[1], normal.z[1]);
}

/// {a.depth(x[0], y), b.depth(x[1], y)}, bit for bit.
[[nodiscard]] inline DoublePair plane_depth_pair(const TrianglePlane& a, const TrianglePlane& b,
                                                 DoublePair x, double y) {
  const DoublePair numerator = {a.numerator, b.numerator};
  const DoublePair nx = {a.normal.x(), b.normal.x()};
  const DoublePair ny = {a.normal.y(), b.normal.y()};
  const DoublePair nz = {a.normal.z(), b.normal.z()};
  const DoublePair ys = {y, y};
  return numerator / ((nx * x + ny * ys) + nz);
}

}  // namespace kinray
