#pragma once
// The Embree reference backend: at each frame time the camera-space vertices are interpolated
// (CameraSpaceObject::positions_at, the same interpolation every backend uses), handed to Embree
// as float triangles, and the pixel-centre rays d_ij = (x_i, y_j, 1) are traced from the eye with
// tnear 0. It is the peer every speed figure is measured against, so it is configured as Embree's
// best users would: one device for the process, robust scenes, FTZ/DAZ on every render thread,
// padded vertex buffers reused between frames, an error callback, all cores.
//
// Modes (BackendConfig::embree_build):
//  - "refit":   one persistent two-level scene (RTC_SCENE_FLAG_DYNAMIC | ROBUST, scene quality
//               LOW); moving objects are RTC_BUILD_QUALITY_REFIT geometries whose vertex buffers
//               are updated and refitted each frame, static objects are built once (HIGH).
//  - "rebuild": a new scene each frame, built from scratch; the geometries and their buffers are
//               reused, only the moving vertices are rewritten.
// Packets (BackendConfig::embree_packet): 1 (rtcIntersect1), 4, 8 or 16 (rtcIntersect4/8/16 over
// 2x2, 4x2 and 4x4 pixel tiles with valid masks).
//
// Depth: Embree's float tfar carries the rounding of its float intersector (an ulp or two off the
// camera-space z). The backend reports instead the exact depth of the triangle Embree hit, z =
// det(v0, v1, v2) / ((v1 - v0) x (v2 - v0)) . d in double from the interpolated camera-space
// positions (docs/design.md, "Depth order per pixel"), so that depths from different backends
// compare exactly. The object and primitive ids are Embree's.
#include <memory>
#include <vector>

#include "renderer/backends/backend.h"

namespace kinray {

/// Creates the Embree backend for `scene` (which must outlive it). Throws OptionError for a bad
/// size, thread count or packet width, std::runtime_error when Embree reports an error.
/// The ray packet widths this machine's Embree traces natively, ascending: 1 always, and 4, 8
/// and 16 where the build and the CPU have them (16 needs AVX-512). Other widths are refused.
/// The process has one Embree device: the first call here or to make_embree_backend creates it,
/// with `threads` build threads (0: all cores).
[[nodiscard]] std::vector<int> embree_packet_widths(int threads = 0);

[[nodiscard]] std::unique_ptr<Backend> make_embree_backend(const CameraSpaceScene& scene,
                                                           const BackendConfig& config);

}  // namespace kinray
