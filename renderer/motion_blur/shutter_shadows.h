#pragma once
// Motion blur with lights (docs/design.md, "Exact motion blur"): while a pixel's front is fixed,
// its shading still changes where a shadow boundary sweeps over the hit point, and there the
// shading jumps. A quadrature across the jump would smear it by the weight of a node, so each
// front interval is cut where its light mask changes and integrated piecewise:
//   1. the mask (bit l: light l faces the hit, its Lambert term on the smooth normal is
//      positive, and its shadow ray is free) is probed at the interval's ends and at its
//      Gauss-Legendre nodes; the Lambert term's clamp at zero is a kink in the shading that a
//      rule across it integrates slowly, and a bit cleared there changes no colour;
//   2. between two probes whose masks differ, each light that differs is bisected until the
//      change time is bracketed to kChangeTimePrecision of the window's length;
//   3. the interval, cut at those times and at its object's keys, is integrated with a
//      Gauss-Legendre rule on every piece (the front's: a textured one's has more nodes, each
//      showing its texture's mean over the node's cell, texture_path.h), each piece under its
//      own constant mask.
// A mask that changes and changes back between two adjacent probes (an occluder narrower than
// the node spacing crossing the light's path) is missed; every other change is found, to the
// precision stated. Shadow rays go through a tree whose boxes bound the window (WindowBvh), so
// each is answered exactly at its own time.
#include <array>
#include <cstdint>
#include <vector>

#include "kinetic/tree/window_bvh.h"
#include "renderer/motion_blur/shutter.h"
#include "renderer/shading.h"
#include "renderer/shadows/shadow_rays.h"
#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

/// Each change time of a light mask is found to within this fraction of the window's length
/// (the colour it moves is at most this fraction of the jump, far below an 8-bit step).
inline constexpr double kChangeTimePrecision = 1e-6;

/// What a pixel's lit integration did, summed per thread (--stats "shutter").
struct ShutterShadowCounts {
  uint64_t shadow_rays = 0;    ///< traced, probes and bisections
  uint64_t mask_changes = 0;   ///< change times found by bisection
  uint64_t shading_nodes = 0;  ///< shadings of a front at a node
};

class ShutterShadows {
 public:
  /// `scene` and `lights` (not empty) must outlive this; `rule` is the per-piece rule.
  ShutterShadows(const CameraSpaceScene& scene, const CameraSpaceLights& lights,
                 const GaussLegendre& rule);

  /// Sweeps the shadow rays' tree over the window: call before the window's integrations.
  void begin_window(const ShutterWindow& window);
  /// Adds the lit shading of (object, prim) seen along pixel direction d over [t0, t1] (inside
  /// the window) to `average`, weighted as shares of the window: the masks probed at the
  /// constructor's rule, the pieces shaded by `shading` (a textured front's may have more nodes).
  /// Thread-safe.
  void integrate(uint32_t object, uint32_t prim, const Vec3& d, double t0, double t1,
                 const GaussLegendre& shading, ColorAverage& average,
                 ShutterShadowCounts& counts) const;
  /// The light mask of (object, prim) along d at time t of the window (Frame::lit).
  [[nodiscard]] uint32_t mask_at(uint32_t object, uint32_t prim, const Vec3& d, double t) const;

 private:
  /// One instant of the front: its lit hit, the lights and its mask there.
  struct Probe;
  /// Per light, the triangle that last blocked its shadow ray in one integration (kNoNode:
  /// none yet), tried first at the next instant (WindowBvh::occluder).
  using OccluderHints = std::array<uint32_t, kMaxLights>;
  /// (`scratch` holds the lights at t when they move.)
  [[nodiscard]] Probe probe(uint32_t object, uint32_t prim, const Vec3& d, double t,
                            ShutterShadowCounts& counts, std::vector<CameraSpaceLight>& scratch,
                            OccluderHints& hints) const;
  /// Whether a triangle other than the one `ray` leaves from meets it at time t (counted); `hint`
  /// is tried first and becomes the triangle found.
  [[nodiscard]] bool blocked(const ShadowRay& ray, double t, ShutterShadowCounts& counts,
                             uint32_t& hint) const;
  /// Whether light l reaches the hit of (object, prim) along d at t.
  [[nodiscard]] bool reaches(uint32_t object, uint32_t prim, const Vec3& d, double t, size_t l,
                             ShutterShadowCounts& counts, std::vector<CameraSpaceLight>& scratch,
                             OccluderHints& hints) const;

  /// The lights at t: m_still_lights when the camera has one key, else `scratch` filled.
  [[nodiscard]] const std::vector<CameraSpaceLight>& lights_at(
      double t, std::vector<CameraSpaceLight>& scratch) const;

  const CameraSpaceScene& m_scene;
  const CameraSpaceLights& m_lights;
  std::vector<CameraSpaceLight> m_still_lights;  ///< when the lights do not move
  const GaussLegendre& m_rule;
  WindowBvh m_tree;
  std::vector<uint32_t> m_first_triangle;  ///< per scene object: its first triangle in the tree
  ShutterWindow m_window;
};

}  // namespace kinray
