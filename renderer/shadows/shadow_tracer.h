#pragma once
// Shadow rays: the seam between the shading pass and the structure that answers occlusion. Every
// backend starts a shadow ray at the same camera-space hit point (the primary hit at the frame
// time) with the same rule against self-intersection (the triangle the ray leaves from is
// skipped), so the shadow masks of two backends can be compared pixel by pixel.
#include <array>
#include <cstdint>
#include <span>
#include <string>

#include <nlohmann/json_fwd.hpp>

#include "scenes/scene.h"
#include "util/enum_names.h"

namespace kinray {

/// What traces the kinetic backend's shadow rays (`--shadow-tree`): a kinetic AABB tree, a
/// kinetic BoxTree, the same AABB tree updated bottom-up at every frame, or every triangle
/// tested (brute force, the reference for small scenes).
enum class ShadowTree { aabb, boxtree, refit, brute };

/// The one spelling of each shadow tracer: --shadow-tree, help, bench --structure, JSON.
inline constexpr std::array kShadowTreeNames{
    EnumName{ShadowTree::aabb, "aabb"},
    EnumName{ShadowTree::boxtree, "boxtree"},
    EnumName{ShadowTree::refit, "refit"},
    EnumName{ShadowTree::brute, "brute"},
};

[[nodiscard]] constexpr const char* shadow_tree_name(ShadowTree kind) {
  return enum_name(kShadowTreeNames, kind);
}

/// One shadow ray in the camera space the backends share (fov-normalized, scenes/camera_space.h):
/// the points origin + s * direction for 0 < s < s_max.
struct ShadowRay {
  Vec3 origin = Vec3::Zero();     ///< the primary hit point
  Vec3 direction = Vec3::Zero();  ///< towards the light, not necessarily unit length
  double s_max = kInfinity;       ///< the light sits at s_max (a point light), or infinity
  uint32_t object = UINT32_MAX;   ///< the triangle the ray leaves from, never an occluder
  uint32_t prim = UINT32_MAX;
};

/// Answers occlusion of shadow rays at a frame time. Frame times never decrease between calls,
/// so a kinetic structure can advance its events instead of rebuilding.
class ShadowTracer {
 public:
  virtual ~ShadowTracer() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  /// Brings the structure to frame time t (t never decreases between calls).
  virtual void advance_to(double t) = 0;
  /// blocked[i] = 1 when some triangle present at the current time, other than the one ray i
  /// leaves from, meets the ray at 0 < s < s_max; else 0.
  /// The shading pass (renderer/shadows/lighting.h) calls it concurrently from its threads, one call per
  /// image row, between advance_to calls.
  virtual void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const = 0;
  /// Adds this tracer's counters and timings to a --stats JSON object.
  virtual void write_stats(nlohmann::json& stats) const {}
};

}  // namespace kinray
