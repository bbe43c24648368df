#pragma once
// Flat regions of meshes: a cloth lying flat, a sphere's equator in z = 0. When three of a
// primitive pair's four points stay on one axis-aligned plane z = c over the whole segment (their
// coordinate is exactly c at both ends) and the fourth point Q never reaches it, the coplanarity
// cubic is exactly (z_Q - c) times the three points' orientation in the plane, and a contact is
// the one planar point on the segment of the other two: a barycentric sign (or an edge
// parameter) of the general test vanishes identically at every such contact, which no error
// bound can certify, while this test's signs stay clear of zero (interval_ccd.cpp).
#include <array>
#include <optional>

#include "kinetic/collision/contact_pair.h"

namespace kinray {

/// The roles of a pair's points (indices into PrimitiveMotion) when three lie on an axis plane
/// that the fourth never meets.
struct AxisPlaneTriple {
  /// Vertex-face whose vertex is the fourth point and whose face lies in the plane: the vertex
  /// is never on the plane, so the pair never touches.
  bool apart = false;
  /// Otherwise the pair touches exactly when the three are collinear (the cubic's roots) with
  /// `point` on the closed segment `segment` (vertex-face: the vertex and the face's two planar
  /// corners; edge-edge: the planar end of one edge and the other, planar, edge).
  int point = 0;
  std::array<int, 2> segment{};
};

/// The roles, when some axis plane holds exactly three of the points over the whole segment and
/// the fourth is on one side of it at both ends (so on neither end nor in between); else none.
[[nodiscard]] std::optional<AxisPlaneTriple> axis_plane_triple(ContactType type,
                                                               const PrimitiveMotion& motion);

/// The axis of a plane that holds all four points over the whole segment (coplanar motion in
/// it: edges sliding over one another in a flat region), if any.
[[nodiscard]] std::optional<int> common_axis_plane(const PrimitiveMotion& motion);

}  // namespace kinray
