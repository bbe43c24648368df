#pragma once
// Shading shared by every backend: the backends only decide which triangle each pixel's centre
// ray hits; the colour is computed here from (object, prim) alone, so frames whose ID buffers
// agree have identical colours.
#include "renderer/frame.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

inline const Color kBackgroundColor(0.06f, 0.07f, 0.09f);
/// The share of the base colour that every hit receives, lit or not.
inline constexpr float kAmbient = 0.15f;
/// The share a light at normal incidence adds (white light: ambient + diffuse = 1).
inline constexpr float kDiffuse = 0.85f;

/// What shading needs of the exact hit of pixel (i, j) on (object, prim) at time t.
struct SurfacePoint {
  Vec3 ray = Vec3::Zero();                                       ///< the pixel's direction d_ij
  Vec3 p0 = Vec3::Zero(), p1 = Vec3::Zero(), p2 = Vec3::Zero();  ///< camera-space vertices at t
  Eigen::Vector3f normal =
      Eigen::Vector3f(0, 0, -1);  ///< interpolated vertex normal, true camera space
  Eigen::Vector3f view = Eigen::Vector3f(0, 0, 1);  ///< unit view direction, true camera space
  double tan_half_fov = 1;                          ///< undoes the fov folding (unfold())
  Color base = Color::Zero();                       ///< base colour times texture
};

/// What every pixel's shading on one object at one time shares: where the time falls on the
/// object's keys and the camera's field of view. Motion blur shades many pixels at the same
/// quadrature nodes and computes this once per node.
struct ShadingInstant {
  KeySegment segment;       ///< the time on the object's key_times
  double tan_half_fov = 1;  ///< CameraSpaceScene::tan_half_fov at the time
};

/// The ShadingInstant of `object` at time t.
[[nodiscard]] ShadingInstant shading_instant(const CameraSpaceScene& scene, uint32_t object,
                                             double t);

/// The SurfacePoint of pixel (i, j) hitting (object, prim) at `instant`.
[[nodiscard]] SurfacePoint surface_point(const CameraSpaceScene& scene, const PixelRays& image,
                                         int i, int j, uint32_t object, uint32_t prim,
                                         const ShadingInstant& instant);

/// The SurfacePoint of pixel (i, j) hitting (object, prim) at time t.
[[nodiscard]] SurfacePoint surface_point(const CameraSpaceScene& scene, const PixelRays& image,
                                         int i, int j, uint32_t object, uint32_t prim, double t);

/// Base colour (or texture) with a two-sided headlight Lambert term, using vertex normals
/// interpolated at the exact hit of pixel (i, j) on (object, prim) at time t.
[[nodiscard]] Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i,
                              int j, uint32_t object, uint32_t prim, double t);

/// shade_hit at `instant` (the same colour as at its time, bit for bit).
[[nodiscard]] Color shade_hit(const CameraSpaceScene& scene, const PixelRays& image, int i,
                              int j, uint32_t object, uint32_t prim, const ShadingInstant& instant);

/// Fills frame.color from frame.object / frame.prim (all cores).
void shade_frame(const CameraSpaceScene& scene, Frame& frame, int threads = 0);

}  // namespace kinray
