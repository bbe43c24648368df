#pragma once
// The sampling peer of exact antialiasing (docs/design.md, "Exact antialiasing"), as Embree's
// users antialias: N = m x m primary rays per pixel at stratified jittered positions of its
// square (pixel_samples.h), each shaded as a centre ray is (shading.h's headlight, or with lights
// renderer/shadows/lighting.h's Lambert term with one shadow ray per light through the same
// scene), averaged with equal weights: a box filter whose error falls as N grows.
#include <embree3/rtcore.h>

#include "renderer/frame.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

/// Fills frame.color with the mean of `samples` (a square) shaded rays per pixel, traced in
/// `scene`: committed with the geometry at frame.time, geometry id = object index (and, with
/// lights, EmbreeShadowTracer's filter on every geometry). With `lights` (not empty) samples are
/// lit and shadowed, and frame.lit is the light mask of the centre hit that frame.object and
/// frame.prim already hold; else the headlight. The primary rays go `packet` at a time (1, 4, 8
/// or 16: the backend's packet width, within a pixel). Rows in parallel on `threads`.
void embree_supersample(RTCScene scene, const CameraSpaceScene& camera_space,
                        const CameraSpaceLights* lights, int samples, int packet, int threads,
                        Frame& frame);

}  // namespace kinray
