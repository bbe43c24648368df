#pragma once
// The orientation O(s) = det(v0(s), v1(s), v2(s)) of a moving triangle decides whether it can
// cover anything at all (the sign rule needs O != 0). Formed in double, O of a triangle whose
// three vertices are collinear (zero area: BART's kitchen has such slivers) is rounding noise
// (6.5e-19 for a vertical sliver of the kitchen at t = 7.18 s) instead of zero, so the sliver
// covered pixels whose ray is parallel to its plane, at infinite depth, and broke the depth
// order's audit. When every coefficient of the rounded O is within its rounding bound of zero,
// O is formed again exactly.
#include "kinetic/core/polynomial.h"

namespace kinray {

struct TriangleMotion;

/// The exact cubic det(v0, v1, v2) of the triangle's vertex motions, every coefficient rounded
/// toward zero from its exact rational value: zero exactly when it is zero, of the exact sign
/// otherwise.
[[nodiscard]] Polynomial exact_orientation(const TriangleMotion& m);

}  // namespace kinray
