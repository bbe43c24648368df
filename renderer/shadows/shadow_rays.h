#pragma once
// Where a pixel's shadow rays start and where they go, computed from the pixel's (object, prim)
// alone, so that two backends that agree on the primary hit trace exactly the same shadow rays
// (and `kinray diff` can recompute them): the origin is the exact hit of the pixel's centre ray
// on the triangle's plane at the frame time, in double, the direction points at the light.
#include <cstddef>
#include <optional>

#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

/// Lights a frame can record: Frame::lit holds one bit per light.
inline constexpr size_t kMaxLights = 32;

/// The point where ray d (from the eye) meets the plane of (p0, p1, p2): d z with
/// z = det(p0, p1, p2) / ((p1 - p0) x (p2 - p0)) . d, the depth every backend reports. A plane
/// seen edge-on (no finite positive z) gives the centroid.
[[nodiscard]] Vec3 plane_hit(const Vec3& d, const Vec3& p0, const Vec3& p1, const Vec3& p2);

/// The shadow ray from `origin`, a point of triangle (p0, p1, p2) = (object, prim), towards
/// `light`, skipping that triangle; nullopt when the light is not strictly on the side of the
/// triangle's plane that the pixel ray d comes from (the visible side faces away from it).
[[nodiscard]] std::optional<ShadowRay> shadow_ray(const Vec3& origin, const Vec3& d, const Vec3& p0,
                                                  const Vec3& p1, const Vec3& p2,
                                                  const CameraSpaceLight& light, uint32_t object,
                                                  uint32_t prim);

}  // namespace kinray
