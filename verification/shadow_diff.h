#pragma once
// Comparing the shadow masks (Frame::lit) of two frames of the same scene at the same time. Only
// pixels where both frames see the same triangle are compared (elsewhere the primary comparison
// of image_diff.h decides), light by light. A light whose bit differs is a *tie* when the shadow
// ray -- recomputed in double exactly as shading made it -- grazes an edge or vertex of some
// triangle, or meets a triangle's plane within rounding of its start (a shadow boundary through
// the hit point) or of the light; otherwise the occlusion is decided robustly by some triangle (or
// by none), the backend that disagrees is wrong, and the pixel is a *real* mismatch.
#include <cstddef>
#include <vector>

#include "renderer/frame.h"
#include "renderer/shadows/shadow_rays.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

/// Tolerances of the shadow tie classification (docs/verification.md justifies them).
struct ShadowTolerance {
  /// ShadowCrossing::edge_margin at or below which a ray grazes an edge (units of float rounding)
  double edge = 1e-5;
  /// |s| |w| cos / (|largest vertex| + |origin|) at or below which a ray starts on (or, from the
  /// light, ends on) a triangle's plane; cos, the incidence, is capped below at 1e-3
  double distance = 1e-5;
};

/// How one light's shadow ray at one pixel compares.
enum class ShadowClass : uint8_t { kTie, kReal };

/// Counts of one light over a frame.
struct LightMismatches {
  size_t real = 0, tie = 0;
};

/// Per-light mismatch counts of two frames' masks and, per pixel, the worst class (nullopt:
/// the masks agree or the primary hits differ). When either frame has no masks (no lights, or
/// read back from files) nothing is compared and `lights` is empty.
struct ShadowDiff {
  std::vector<LightMismatches> lights;
  std::vector<int8_t> pixels;  ///< -1: agree, else ShadowClass
};
[[nodiscard]] ShadowDiff compare_shadows(const CameraSpaceScene& scene,
                                         const CameraSpaceLights& lights, const Frame& tested,
                                         const Frame& reference,
                                         const ShadowTolerance& tolerance = {});

}  // namespace kinray
