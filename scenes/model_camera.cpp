#include "scenes/model_camera.h"

#include <assimp/camera.h>
#include <assimp/scene.h>

#include <cmath>

#include "util/input_error.h"

namespace kinray {

std::optional<NamedCamera> model_camera(const aiScene& scene, const NodeGraph& graph,
                                        std::span<const double> key_seconds,
                                        std::span<const double> key_ticks,
                                        const std::string& where) {
  for (unsigned c = 0; c < scene.mNumCameras && scene.mCameras != nullptr; ++c) {
    const aiCamera* camera = scene.mCameras[c];
    if (camera == nullptr) continue;
    const std::string name = camera->mName.C_Str();
    const std::string camera_where = where + ": camera '" + name + "'";
    const int node = graph.find(name);
    if (node < 0) continue;
    if (camera->mOrthographicWidth > 0) {
      warn_repair(camera_where, "is orthographic, which kinray does not render; skipped");
      continue;
    }
    const Vec3 position = to_eigen(camera->mPosition), look = to_eigen(camera->mLookAt),
               up = to_eigen(camera->mUp);
    if (!position.allFinite() || !look.allFinite() || !up.allFinite() || look.norm() == 0 ||
        up.norm() == 0)
      throw InputError(camera_where, "has a NaN, infinite or zero position or direction");
    double horizontal = camera->mHorizontalFOV;
    if (!std::isfinite(horizontal) || horizontal <= 0 || horizontal >= M_PI) {
      warn_repair(camera_where, "has no usable field of view; using " +
                                    std::to_string(int(kFramingFovDegrees)) +
                                    " degrees vertically");
      horizontal = 2 * std::atan(std::tan(kFramingFovDegrees * M_PI / 360));
    }
    const double aspect =
        std::isfinite(camera->mAspect) && camera->mAspect > 0 ? double(camera->mAspect) : 1.0;
    const double fov_y =
        std::clamp(2 * std::atan(std::tan(horizontal / 2) / aspect) * 180 / M_PI, 1.0, 179.0);

    NamedCamera result{name, {}};
    result.camera.keys.clear();
    const size_t count = graph.moves(node) ? key_seconds.size() : 1;
    std::vector<Mat4> globals;
    for (size_t k = 0; k < count; ++k) {
      graph.global_transforms(key_ticks[k], globals);
      const Mat4& g = globals[size_t(node)];
      const Eigen::Matrix3d linear = g.topLeftCorner<3, 3>();
      const Vec3 eye = transform_point(g, position);
      const Vec3 forward = linear * look, world_up = linear * up;
      if (!eye.allFinite() || !forward.allFinite() || forward.norm() < 1e-300)
        throw InputError(camera_where, "its node places it at a NaN or degenerate position");
      result.camera.keys.push_back(
          Camera::look_at(key_seconds[k], eye, eye + forward.normalized(), world_up, fov_y));
    }
    return result;
  }
  return std::nullopt;
}

bool camera_sees(const Camera& camera, const Scene& scene) {
  for (const CameraKey& key : camera.keys) {
    const Eigen::Matrix3d world_to_camera =
        key.orientation.normalized().toRotationMatrix().transpose();
    const double slope = std::tan(key.fov_y_degrees * M_PI / 360);
    for (const Object& object : scene.objects)
      for (uint32_t v = 0; v < object.vertex_count(); ++v) {
        const Vec3 p = world_to_camera * (object.position(v, key.time) - key.position);
        const double depth = -p.z();  // the stored camera frame looks down -z
        if (depth > 0 && std::abs(p.x()) <= slope * depth && std::abs(p.y()) <= slope * depth)
          return true;
      }
  }
  return false;
}

}  // namespace kinray
