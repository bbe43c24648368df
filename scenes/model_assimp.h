#pragma once
// The boundary between assimp and kinray: assimp's math types in Eigen form, and the one way the
// model importer reports a repair (a warning, util/warning.h; stdout stays clean for the tools).
#include <assimp/matrix4x4.h>
#include <assimp/quaternion.h>
#include <assimp/vector3.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>

#include "scenes/scene.h"

namespace kinray {

using Mat4 = Eigen::Matrix4d;

/// assimp matrices act on column vectors (translation in a4, b4, c4), like Eigen's.
[[nodiscard]] inline Mat4 to_eigen(const aiMatrix4x4& m) {
  Mat4 result;
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) result(r, c) = double(m[r][c]);
  return result;
}
[[nodiscard]] inline Vec3 to_eigen(const aiVector3D& v) {
  return {double(v.x), double(v.y), double(v.z)};
}
[[nodiscard]] inline Eigen::Quaterniond to_eigen(const aiQuaternion& q) {
  return {double(q.w), double(q.x), double(q.y), double(q.z)};
}
/// Applies an affine 4x4 transform to a point.
[[nodiscard]] inline Vec3 transform_point(const Mat4& m, const Vec3& p) {
  return m.topLeftCorner<3, 3>() * p + m.topRightCorner<3, 1>();
}

/// The problem with a model vertex that is not finite. assimp reads positions as float, so a
/// coordinate beyond float's range in the file (1e300, say) arrives here as infinite: the message
/// says so rather than leaving the user to wonder where an infinity came from.
[[nodiscard]] inline std::string non_finite_vertex(size_t v) {
  return "vertex " + std::to_string(v) +
         " is NaN or infinite as a float (a coordinate beyond +-3.4e38, which the float "
         "references cannot represent, reads as infinite)";
}

/// Reports a documented repair of bad model data: one warning (util/warning.h) naming the place.
void warn_repair(const std::string& where, const std::string& what);

}  // namespace kinray
