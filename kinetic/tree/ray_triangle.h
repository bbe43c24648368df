#pragma once
// The ray-triangle test of the kinetic trees' queries (Moeller-Trumbore in double), shared by the
// trees and the brute-force references of the tests so that they decide every ray alike.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <optional>

namespace kinray {

/// The ray parameter s at which origin + s direction meets the triangle (p0, p1, p2), edges
/// included; std::nullopt when it misses or the triangle is degenerate in the ray's view.
[[nodiscard]] inline std::optional<double> ray_triangle(const Eigen::Vector3d& origin,
                                                        const Eigen::Vector3d& direction,
                                                        const Eigen::Vector3d& p0,
                                                        const Eigen::Vector3d& p1,
                                                        const Eigen::Vector3d& p2) {
  const Eigen::Vector3d e1 = p1 - p0, e2 = p2 - p0;
  const Eigen::Vector3d p = direction.cross(e2);
  const double det = e1.dot(p);
  if (det == 0 || !std::isfinite(det)) return std::nullopt;
  const double inv = 1.0 / det;
  const Eigen::Vector3d o = origin - p0;
  const double u = o.dot(p) * inv;
  if (u < 0 || u > 1) return std::nullopt;
  const Eigen::Vector3d q = o.cross(e1);
  const double v = direction.dot(q) * inv;
  if (v < 0 || u + v > 1) return std::nullopt;
  return e2.dot(q) * inv;
}

}  // namespace kinray
