#pragma once
// The scene's world-space lights in the camera space the backends share (scenes/camera_space.h):
// transformed at every camera key and interpolated linearly between keys, exactly as the
// positions of a static object are, so a light placed on a surface stays on it in camera space.
// Positions and directions carry the fov folding (x and y scaled by 1 / tan(fov_y / 2)); side
// tests and ray parameters are unchanged by it, Lambert terms undo it (unfold()).
#include <vector>

#include "scenes/scene.h"

namespace kinray {

/// One light at one time in fov-normalized camera space.
struct CameraSpaceLight {
  Light::Kind kind = Light::Kind::point;
  Vec3 position = Vec3::Zero();   ///< point lights
  Vec3 towards = Vec3(0, 0, -1);  ///< directional lights: from the scene towards the light
  Color color = Color(1.0f, 1.0f, 1.0f);
  /// The vector from `point` towards the light: light position - point (reached at parameter
  /// 1), or `towards` (never reached).
  [[nodiscard]] Vec3 vector_from(const Vec3& point) const {
    return kind == Light::Kind::point ? Vec3(position - point) : towards;
  }
};

/// The lights of a scene in camera space at any time.
class CameraSpaceLights {
 public:
  CameraSpaceLights() = default;
  explicit CameraSpaceLights(const Scene& scene);
  [[nodiscard]] bool empty() const { return m_count == 0; }
  [[nodiscard]] size_t size() const { return m_count; }
  /// The camera has one key: every light is where at(t) says at any time.
  [[nodiscard]] bool still() const { return m_key_times.size() < 2; }
  /// Every light at time t (the camera keys' transforms interpolated linearly).
  [[nodiscard]] std::vector<CameraSpaceLight> at(double t) const;
  /// The same into `out`, reusing its storage (motion blur asks at every node of every pixel).
  void at(double t, std::vector<CameraSpaceLight>& out) const;

 private:
  size_t m_count = 0;
  std::vector<double> m_key_times;       ///< the camera's key times, at least one
  std::vector<CameraSpaceLight> m_keys;  ///< [key * m_count + light]
};

/// Undoes the fov folding of a camera-space vector: true camera space, for angles.
[[nodiscard]] inline Vec3 unfold(const Vec3& v, double tan_half_fov) {
  return {v.x() * tan_half_fov, v.y() * tan_half_fov, v.z()};
}

}  // namespace kinray
