#pragma once
// Lambert shading with shadows from every light of the scene (the headlight of shading.h is
// used when the scene has none). Per pixel and light, a shadow ray from the primary hit
// (shadow_rays.h) asks the backend's ShadowTracer whether the light reaches the hit; the answers
// go to Frame::lit (bit l for light l) and the colour is
//   base * (ambient + diffuse * sum over reaching lights of colour_l * max(0, n . l)),
// n the interpolated vertex normal turned towards the eye, l the unit vector to the light in true
// camera space. Lights do not fall off with distance: a light's colour is its irradiance.
#include <cstdint>
#include <optional>
#include <type_traits>
#include <vector>

#include "renderer/frame.h"
#include "renderer/shading.h"
#include "renderer/shadows/shadow_rays.h"
#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

/// The hit of a pixel's ray on a triangle at one instant, with what its lit shading and its
/// shadow rays start from: the surface point and the exact hit on the triangle's plane.
struct LitHit {
  SurfacePoint surface;
  Vec3 origin = Vec3::Zero();
};

/// The LitHit of pixel direction d on `triangle` (its view direction given, as surface_point
/// takes it).
[[nodiscard]] LitHit lit_hit(const TriangleAtInstant& triangle, const Vec3& d,
                             const Eigen::Vector3f& view);

/// The LitHit of pixel direction d on (object, prim) at time t, as every backend shades it.
[[nodiscard]] LitHit lit_hit(const CameraSpaceScene& scene, uint32_t object, uint32_t prim,
                             const Vec3& d, double t);

/// The shadow ray of `hit` on (object, prim) towards light l; nullopt when the light does not face
/// the visible side (shadow_rays.h).
[[nodiscard]] inline std::optional<ShadowRay> shadow_ray(const LitHit& hit,
                                                         const CameraSpaceLight& light,
                                                         uint32_t object, uint32_t prim) {
  const SurfacePoint& s = hit.surface;
  return shadow_ray(hit.origin, s.ray, s.p0, s.p1, s.p2, light, object, prim);
}

/// Bit l set when light l (among `candidates`) faces `hit` and its shadow ray is not blocked:
/// blocked(ray), or blocked(ray, l), answers.
template <class Blocked>
[[nodiscard]] uint32_t light_mask(const LitHit& hit, const std::vector<CameraSpaceLight>& lights,
                                  uint32_t object, uint32_t prim, Blocked&& blocked,
                                  uint32_t candidates = ~0u) {
  uint32_t mask = 0;
  for (size_t l = 0; l < lights.size(); ++l)
    if (const auto ray =
            (candidates >> l & 1u) != 0 ? shadow_ray(hit, lights[l], object, prim) : std::nullopt;
        ray) {
      bool shadowed = false;
      if constexpr (std::is_invocable_v<Blocked, const ShadowRay&, size_t>)
        shadowed = blocked(*ray, l);
      else
        shadowed = blocked(*ray);
      if (!shadowed) mask |= 1u << l;
    }
  return mask;
}

/// The interpolated normal turned towards the eye (the visible side), as lit_color shades it.
[[nodiscard]] Eigen::Vector3f visible_normal(const SurfacePoint& surface);
/// n . (unit direction from `origin` to the light): the light's Lambert term at the surface point
/// before lit_color clamps it at zero, n the visible normal.
[[nodiscard]] float lambert_term(const Eigen::Vector3f& n, const SurfacePoint& surface,
                                 const Vec3& origin, const CameraSpaceLight& light);

/// Bit l set when light l's Lambert term at the surface point is positive: the interpolated
/// normal, turned towards the eye, against the direction to the light, with lit_color's own
/// arithmetic. Where it is not, lit_color adds nothing for the light, so a mask that also
/// clears those bits shades the same; its change is the shading's kink at the smooth terminator.
[[nodiscard]] uint32_t lit_side_mask(const SurfacePoint& surface, const Vec3& origin,
                                     const std::vector<CameraSpaceLight>& lights);
[[nodiscard]] inline uint32_t lit_side_mask(const LitHit& hit,
                                            const std::vector<CameraSpaceLight>& lights) {
  return lit_side_mask(hit.surface, hit.origin, lights);
}

/// The Lambert colour of a surface point lit by the lights of `mask` (bit l: light l reaches
/// it), `origin` its exact hit.
[[nodiscard]] Color lit_color(const SurfacePoint& surface, const Vec3& origin,
                              const std::vector<CameraSpaceLight>& lights, uint32_t mask);
[[nodiscard]] inline Color lit_color(const LitHit& hit, const std::vector<CameraSpaceLight>& lights,
                                     uint32_t mask) {
  return lit_color(hit.surface, hit.origin, lights, mask);
}

/// Brings `tracer` to frame.time, traces every pixel's shadow rays (rows in parallel, `threads`
/// as parallel_for takes them; the tracer's occluded() is called concurrently) and fills
/// frame.lit and frame.color. `lights` must not be empty nor hold more than kMaxLights.
void shade_frame_lit(const CameraSpaceScene& scene, const CameraSpaceLights& lights,
                     ShadowTracer& tracer, Frame& frame, int threads = 0);

}  // namespace kinray
