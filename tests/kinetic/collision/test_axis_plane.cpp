// The roles of a pair's points when three of them lie on an axis plane that the fourth never
// meets.
#include <gtest/gtest.h>

#include "kinetic/collision/axis_plane.h"

namespace kinray {
namespace {

using V = Eigen::Vector3d;

TEST(AxisPlane, FindsThePointAndTheSegmentOnThePlane) {
  // the face's corner 2 above z = 0.5, everything else on it
  PrimitiveMotion m = {{V(0.2, 0.1, 0.5), V(0, 0, 0.5), V(1, 0, 1.5), V(0, 1, 0.5)},
                       {V(0.3, 0.4, 0.5), V(0, 0, 0.5), V(1, 0, 2.5), V(0, 1, 0.5)}};
  std::optional<AxisPlaneTriple> roles = axis_plane_triple(ContactType::vertex_face, m);
  ASSERT_TRUE(roles);
  EXPECT_FALSE(roles->apart);
  EXPECT_EQ(roles->point, 0);
  EXPECT_EQ(roles->segment, (std::array<int, 2>{1, 3}));
  // as edges (p0, p1) and (p2, p3): p2 leaves the plane, so p3 meets edge (p0, p1)
  roles = axis_plane_triple(ContactType::edge_edge, m);
  ASSERT_TRUE(roles);
  EXPECT_EQ(roles->point, 3);
  EXPECT_EQ(roles->segment, (std::array<int, 2>{0, 1}));
  // the vertex off the plane of its face: apart
  std::swap(m.start[0], m.start[2]);
  std::swap(m.end[0], m.end[2]);
  roles = axis_plane_triple(ContactType::vertex_face, m);
  ASSERT_TRUE(roles);
  EXPECT_TRUE(roles->apart);
}

TEST(AxisPlane, NoRolesWhenTheFourthPointMeetsThePlane) {
  // corner 2 crosses z = 0.5 during the segment, then ends on it: the plane may hold all four
  PrimitiveMotion m = {{V(0.2, 0.1, 0.5), V(0, 0, 0.5), V(1, 0, 1.5), V(0, 1, 0.5)},
                       {V(0.3, 0.4, 0.5), V(0, 0, 0.5), V(1, 0, -1), V(0, 1, 0.5)}};
  EXPECT_FALSE(axis_plane_triple(ContactType::vertex_face, m));
  m.end[2].z() = 0.5;
  EXPECT_FALSE(axis_plane_triple(ContactType::vertex_face, m));
  // all four on the plane (coplanar motion) is not this case either
  m.start[2].z() = 0.5;
  EXPECT_FALSE(axis_plane_triple(ContactType::vertex_face, m));
  // a point that leaves the plane during the segment is not on it
  m = {{V(0.2, 0.1, 0.5), V(0, 0, 0.5), V(1, 0, 1.5), V(0, 1, 0.5)},
       {V(0.3, 0.4, 0.5), V(0, 0, 0.7), V(1, 0, 2.5), V(0, 1, 0.5)}};
  EXPECT_FALSE(axis_plane_triple(ContactType::vertex_face, m));
}

TEST(AxisPlane, FindsThePlaneOfCoplanarMotion) {
  PrimitiveMotion m = {{V(0.2, 0.5, 0.1), V(0, 0.5, 0), V(1, 0.5, 1), V(0, 0.5, 1)},
                       {V(0.3, 0.5, 0.4), V(0, 0.5, 0), V(1, 0.5, 2), V(0, 0.5, 1)}};
  EXPECT_EQ(common_axis_plane(m), 1);
  m.end[2].y() = 0.6;  // leaves the plane
  EXPECT_FALSE(common_axis_plane(m));
}

}  // namespace
}  // namespace kinray
