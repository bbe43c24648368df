#pragma once
// TrianglePlane::depth of two pixels at once, for the read-out: one division per covered pixel is
// most of its arithmetic, and a two-lane vector does two divisions for the price of one. Lane for
// lane the operations are those of TrianglePlane::depth -- Eigen sums the dot product of
// (nx, ny, nz) with (x, y, 1) as (nx x + ny y) + nz, the last product being exact -- and IEEE
// arithmetic rounds each lane as it rounds a scalar, so every depth is the same bit for bit
// (tests/kinetic/test_plane_depth_pair.cpp checks this against TrianglePlane::depth).
#include "kinetic/triangle_motion.h"

namespace kinray {

/// Two doubles in one SIMD register (GCC/Clang vector extension: IEEE operations lane by lane).
using DoublePair = double __attribute__((vector_size(16)));

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
