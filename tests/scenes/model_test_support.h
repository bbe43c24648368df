#pragma once
// What the model-import tests check on a loaded scene, computed independently of the importer:
// how far vertices move, and what the camera sees (the camera-space convention of docs/design.md:
// eye at the origin looking down +z, a point is in a square image when |x|, |y| <= z tan(fov/2)).
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <string>

#include "scenes/camera_space.h"
#include "scenes/scene.h"

namespace kinray::testing {

/// Debian's assimp-testmodels.
inline const std::filesystem::path kTestModels = "/usr/share/assimp/models";
/// Models of the shared folder that Debian does not carry.
inline const std::filesystem::path kSharedModels =
    std::filesystem::path(KINRAY_SHARED_DIR) / "data" / "models";

/// Largest distance any vertex moves between its first key and any other key.
inline double largest_motion(const Scene& scene) {
  double largest = 0;
  for (const Object& object : scene.objects)
    for (size_t k = 1; k < object.key_count(); ++k)
      for (size_t v = 0; v < object.vertex_count(); ++v)
        largest =
            std::max(largest, (object.key_positions[k][v] - object.key_positions[0][v]).norm());
  return largest;
}

/// A world point in the camera's frame at t: x right, y up, z = depth along the view.
inline Vec3 to_camera(const Scene& scene, const Vec3& p, double t) {
  const CameraKey key = scene.camera.at(t);
  Vec3 q = key.orientation.normalized().toRotationMatrix().transpose() * (p - key.position);
  q.z() = -q.z();  // stored camera frames look down -z
  return q;
}

/// True when p is in front of the camera and inside its view on a square image.
inline bool in_view(const Scene& scene, const Vec3& p, double t) {
  const Vec3 q = to_camera(scene, p, t);
  const double slope = std::tan(scene.camera.at(t).fov_y_degrees * M_PI / 360);
  return q.z() > 0 && std::abs(q.x()) <= slope * q.z() && std::abs(q.y()) <= slope * q.z();
}

/// Fraction of all vertices inside the view at t.
inline double fraction_in_view(const Scene& scene, double t) {
  size_t inside = 0, all = 0;
  for (const Object& object : scene.objects)
    for (uint32_t v = 0; v < object.vertex_count(); ++v, ++all)
      if (in_view(scene, object.position(v, t), t)) ++inside;
  return all == 0 ? 0.0 : double(inside) / double(all);
}

/// True when all eight corners of the scene's bounds (over every key) are inside the view at t.
inline bool bounds_in_view(const Scene& scene, double t) {
  const Eigen::AlignedBox3d box = scene.bounds();
  for (int corner = 0; corner < 8; ++corner)
    if (!in_view(scene, box.corner(Eigen::AlignedBox3d::CornerType(corner)), t)) return false;
  return true;
}

}  // namespace kinray::testing
