#pragma once
// The objects of a camera-space scene placed at one instant, for the brute-force references that
// test every triangle (renderer/shadows/brute_force_shadow_tracer.h, the coincident-surface check
// of verification/coincident_fronts.h): each present object's positions at the instant and their
// box, and a slab test that culls an object's triangles only where an exact test could not hit
// them.
#include <cstdint>
#include <vector>

#include "scenes/camera_space.h"

namespace kinray {

/// An object present at an instant: visible then, with triangles.
struct PresentObject {
  uint32_t object = 0;                        ///< index into CameraSpaceScene::objects
  std::vector<Vec3> positions;                ///< camera-space positions at the instant
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();  ///< their bounding box
};

/// The objects of `scene` present at time t, into `out` (replaced).
void place_present_objects(const CameraSpaceScene& scene, double t,
                           std::vector<PresentObject>& out);

/// Whether the segment origin + s direction, 0 <= s <= s_max (s_max may be infinite), may meet
/// `object`'s box: a slab test widened by a relative 1e-9, so that rounding never culls a triangle
/// an exact test would hit.
[[nodiscard]] bool segment_may_meet_box(const PresentObject& object, const Vec3& origin,
                                        const Vec3& direction, double s_max);

}  // namespace kinray
