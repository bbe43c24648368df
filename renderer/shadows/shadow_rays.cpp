#include "renderer/shadows/shadow_rays.h"

#include <cmath>

namespace kinray {

Vec3 plane_hit(const Vec3& d, const Vec3& p0, const Vec3& p1, const Vec3& p2) {
  const double numerator = p0.dot(p1.cross(p2));
  const double denominator = (p1 - p0).cross(p2 - p0).dot(d);
  const double z = numerator / denominator;
  if (std::isfinite(z) && z > 0) return d * z;
  return (p0 + p1 + p2) / 3.0;
}

std::optional<ShadowRay> shadow_ray(const Vec3& origin, const Vec3& d, const Vec3& p0,
                                    const Vec3& p1, const Vec3& p2, const CameraSpaceLight& light,
                                    uint32_t object, uint32_t prim) {
  const Vec3 normal = (p1 - p0).cross(p2 - p0);
  const double eye_side = normal.dot(d);  // < 0: the ray meets the front face
  const double light_side = normal.dot(light.vector_from(p0));
  // Strictly opposite signs: eye and light on the same side. The fov folding scales x and y by
  // the same positive factor, so these signs are those of true camera space.
  if (!(eye_side < 0 && light_side > 0) && !(eye_side > 0 && light_side < 0)) return std::nullopt;
  ShadowRay ray;
  ray.origin = origin;
  ray.direction = light.vector_from(origin);
  ray.s_max = light.kind == Light::Kind::point ? 1.0 : kInfinity;
  ray.object = object;
  ray.prim = prim;
  return ray;
}

}  // namespace kinray
