#pragma once
// Lambert shading with shadows from every light of the scene (the headlight of shading.h is
// used when the scene has none). Per pixel and light, a shadow ray from the primary hit
// (shadow_rays.h) asks the backend's ShadowTracer whether the light reaches the hit; the answers
// go to Frame::lit (bit l for light l) and the colour is
//   base * (ambient + diffuse * sum over reaching lights of colour_l * max(0, n . l)),
// n the interpolated vertex normal turned towards the eye, l the unit vector to the light in true
// camera space. Lights do not fall off with distance: a light's colour is its irradiance.
#include "renderer/frame.h"
#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

/// Brings `tracer` to frame.time, traces every pixel's shadow rays (rows in parallel, `threads`
/// as parallel_for takes them; the tracer's occluded() is called concurrently) and fills
/// frame.lit and frame.color. `lights` must not be empty nor hold more than kMaxLights.
void shade_frame_lit(const CameraSpaceScene& scene, const CameraSpaceLights& lights,
                     ShadowTracer& tracer, Frame& frame, int threads = 0);

}  // namespace kinray
