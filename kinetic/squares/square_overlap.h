#pragma once
// The brute-force answer the per-square sets are checked against: does a triangle's image region
// R = { (x, y) : the forward ray (x, y, 1) pierces it } overlap a closed square? R is the
// intersection of the three half-planes sign(E_pq(x, y, 1)) = sign(O) (the sign rule of
// docs/design.md), so the square is clipped by them in double, with no projection and no clipping
// at the eye plane. A tolerance on each half-plane tells a clear answer from a tie (an edge line
// or a vertex on the square's boundary, an orientation near zero), which a caller reports as a tie,
// never as a failure.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace kinray {

enum class Overlap { kNo, kYes, kTie };

/// An axis-aligned closed square [x0, x1] x [y0, y1] of the image plane z = 1.
struct ImageSquare {
  double x0 = 0, x1 = 0, y0 = 0, y1 = 0;
};

/// Whether R of the triangle (p0, p1, p2) (camera space, at one time) overlaps the square: kYes
/// when the square clipped by the half-planes moved inwards by the tolerance is not empty, kNo
/// when the square clipped by them moved outwards is empty, kTie otherwise.
[[nodiscard]] Overlap square_overlap(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                     const Eigen::Vector3d& p2, const ImageSquare& square);

/// Whether the ray (x, y, 1) pierces the triangle by the sign rule: kTie when an edge function or
/// O is within the tolerance of zero.
[[nodiscard]] Overlap ray_pierces(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                                  const Eigen::Vector3d& p2, double x, double y);

}  // namespace kinray
