#include "kinetic/collision/axis_plane.h"

namespace kinray {

namespace {

/// Point i has coordinate c on the axis at both ends of the segment, hence all along it.
bool fixed_at(const PrimitiveMotion& m, int i, int axis, double c) {
  return m.start[size_t(i)][axis] == c && m.end[size_t(i)][axis] == c;
}

}  // namespace

std::optional<AxisPlaneTriple> axis_plane_triple(ContactType type, const PrimitiveMotion& m) {
  for (int axis = 0; axis < 3; ++axis)
    for (int q = 0; q < 4; ++q) {
      // the plane of the three points other than q: that of the first of them
      const int first = q == 0 ? 1 : 0;
      const double c = m.start[size_t(first)][axis];
      bool planar = true;
      for (int i = 0; i < 4 && planar; ++i) planar = i == q || fixed_at(m, i, axis, c);
      if (!planar) continue;
      // Q strictly on one side at both ends, hence all along its linear motion
      const double s = m.start[size_t(q)][axis] - c, e = m.end[size_t(q)][axis] - c;
      if (!((s > 0 && e > 0) || (s < 0 && e < 0))) continue;
      AxisPlaneTriple roles;
      if (type == ContactType::vertex_face) {
        roles.apart = q == 0;
        roles.point = 0;
        roles.segment = {q == 1 ? 2 : 1, q == 3 ? 2 : 3};
      } else {
        const bool on_a = q < 2;  // Q ends edge a: a meets the plane at its other end only
        roles.point = on_a ? 1 - q : 5 - q;
        roles.segment = on_a ? std::array<int, 2>{2, 3} : std::array<int, 2>{0, 1};
      }
      return roles;
    }
  return std::nullopt;
}

std::optional<int> common_axis_plane(const PrimitiveMotion& m) {
  for (int axis = 0; axis < 3; ++axis) {
    const double c = m.start[0][axis];
    bool planar = true;
    for (int i = 0; i < 4 && planar; ++i) planar = fixed_at(m, i, axis, c);
    if (planar) return axis;
  }
  return std::nullopt;
}

}  // namespace kinray
