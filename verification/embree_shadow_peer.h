#pragma once
// Shadow rays through Embree (rtcOccluded1), refitted or rebuilt at each frame time from the same
// interpolated camera-space positions as every backend: the peer of the kinetic trees in
// `kinray bench --structure aabb,boxtree` and their reference in the tests. The triangle a ray
// leaves from is skipped by a context filter, as renderer/shadows/shadow_tracer.h asks.
#include <memory>

#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"

namespace kinray {

/// Embree's answer to shadow rays over `scene` (which must outlive it): `refit` refits one
/// dynamic scene at each advance_to, else the scene is rebuilt from scratch. Builds run on one
/// thread (a device of its own with threads=1).
[[nodiscard]] std::unique_ptr<ShadowTracer> make_embree_shadow_tracer(const CameraSpaceScene& scene,
                                                                      bool refit);

}  // namespace kinray
