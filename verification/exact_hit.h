#pragma once
// A pixel ray against one triangle, exactly (in double from the camera-space positions), with
// the tolerances within which two backends' float arithmetic may disagree: the tie rules of
// `kinray diff` (image_diff.h) and of the blurred frames' coincident surfaces
// (coincident_fronts.h).
#include <array>

#include "scenes/scene.h"

namespace kinray {

/// Tolerances of the tie classification (defaults justified in exact_hit.cpp).
struct TieTolerance {
  double depth = 1e-6;  ///< relative depth difference, per unit of 1 / cos(incidence)
  double edge = 1e-5;   ///< |E_pq(d)| / (|p| |q| |d|): distance of the ray from edge pq
};

/// The exact hit of a pixel ray on one triangle at time t.
struct ExactHit {
  bool valid = false;              ///< the ray pierces the triangle, up to the edge tolerance
  double z = 0;                    ///< depth (the ray parameter)
  double cos = 1;                  ///< |cos| of the angle between the ray and the normal
  std::array<double, 3> margin{};  ///< signed distance from edges (v0 v1), (v1 v2), (v2 v0)
  unsigned near_edges = 0;         ///< bit k: |margin[k]| <= the edge tolerance
};

/// Ray d (from the eye at the origin) against the camera-space triangle v.
[[nodiscard]] ExactHit exact_hit(const std::array<Vec3, 3>& v, const Vec3& d,
                                 double edge_tolerance);

/// Depths equal up to the float precision of the backends.
[[nodiscard]] bool same_depth(const ExactHit& a, const ExactHit& b, const TieTolerance& tolerance);

}  // namespace kinray
