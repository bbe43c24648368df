#pragma once
// The exact depth of a hit: the depth of the hit triangle's plane along the pixel-centre ray
// d = (x, y, 1), det(p0, p1, p2) / ((p1 - p0) x (p2 - p0) . d), in double. Every backend reports
// this instead of its intersector's rounded ray parameter, so depths compare exactly.
#include <cmath>
#include <limits>

#include "scenes/camera_space.h"

namespace kinray {

/// The plane depth along d (not finite when the plane holds the eye or is seen edge-on).
[[nodiscard]] inline double exact_plane_depth(const Vec3& p0, const Vec3& p1, const Vec3& p2,
                                              const Vec3& d) {
  return p0.dot(p1.cross(p2)) / (p1 - p0).cross(p2 - p0).dot(d);
}

/// The plane depth of triangle `prim` of `object` at time t along d, as a float; +inf when it is
/// not a finite positive number.
[[nodiscard]] inline float exact_plane_depth(const CameraSpaceScene& scene, uint32_t object,
                                             uint32_t prim, const Vec3& d, double t) {
  const CameraSpaceObject& cs = scene.objects[object];
  const Triangle& tri = scene.triangles(object)[prim];
  const double z =
      exact_plane_depth(cs.position(tri[0], t), cs.position(tri[1], t), cs.position(tri[2], t), d);
  return std::isfinite(z) && z > 0 ? float(z) : std::numeric_limits<float>::infinity();
}

}  // namespace kinray
