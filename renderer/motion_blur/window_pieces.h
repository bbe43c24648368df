#pragma once
// Where the motion inside a shutter window turns: every key of a moving object and every time an
// object appears or disappears. Between two of these breaks each vertex moves linearly (the
// flightplans are piecewise linear), so what depends smoothly on the positions is smooth there.
// Embree's motion blur builds one scene per piece (embree_motion_blur.h); the exact space-time box
// filter places its quadrature nodes per piece (renderer/antialiasing/exact_shutter.h).
#include <vector>

#include "renderer/motion_blur/shutter.h"
#include "scenes/camera_space.h"

namespace kinray {

/// Whether `object`'s camera-space positions change at all (it has two keys or more, and they
/// differ).
[[nodiscard]] inline bool moves(const CameraSpaceObject& object) {
  return !object.is_static && object.key_times.size() > 1;
}

/// The sorted breaks of `window`: its open and close, and between them every key of a moving
/// object and every appear or disappear time of `scene`, without repeats. Piece k is
/// [breaks[k], breaks[k + 1]]; a window of length zero has the one piece [open, open].
[[nodiscard]] std::vector<double> window_breaks(const CameraSpaceScene& scene,
                                                const ShutterWindow& window);

}  // namespace kinray
