#include "scenes/camera_space_lights.h"

#include <algorithm>
#include <cmath>

#include "scenes/camera_space.h"

namespace kinray {
CameraSpaceLights::CameraSpaceLights(const Scene& scene) : m_count(scene.lights.size()) {
  if (m_count == 0) return;
  for (const CameraKey& key : scene.camera.keys) m_key_times.push_back(key.time);
  m_keys.resize(m_key_times.size() * m_count);
  for (size_t k = 0; k < m_key_times.size(); ++k) {
    const CameraKey& key = scene.camera.keys[k];
    const Eigen::Matrix3d rotation = key.orientation.normalized().toRotationMatrix().transpose();
    Eigen::Matrix3d world_to_camera = rotation;
    world_to_camera.row(2) *= -1.0;  // the stored frame looks down -z; camera space looks down +z
    const double fov_scale = 1.0 / std::tan(key.fov_y_degrees * M_PI / 360.0);
    for (size_t l = 0; l < m_count; ++l) {
      const Light& light = scene.lights[l];
      CameraSpaceLight& out = m_keys[k * m_count + l];
      out.kind = light.kind;
      out.color = light.color;
      // The same two steps as the vertices: rotate into true camera space, then fold the fov.
      const Vec3 p = world_to_camera * (light.position - key.position);
      const Vec3 w = world_to_camera * (-light.direction);
      out.position = Vec3(p.x() * fov_scale, p.y() * fov_scale, p.z());
      out.towards = Vec3(w.x() * fov_scale, w.y() * fov_scale, w.z());
    }
  }
}

std::vector<CameraSpaceLight> CameraSpaceLights::at(double t) const {
  std::vector<CameraSpaceLight> lights;
  at(t, lights);
  return lights;
}

void CameraSpaceLights::at(double t, std::vector<CameraSpaceLight>& out) const {
  out.assign(m_keys.begin(), m_keys.begin() + std::ptrdiff_t(std::min(m_count, m_keys.size())));
  if (m_key_times.size() < 2) return;
  const KeySegment s = locate(m_key_times, t);
  for (size_t l = 0; l < m_count; ++l) {
    const CameraSpaceLight& a = m_keys[s.k * m_count + l];
    const CameraSpaceLight& b = m_keys[(s.k + 1) * m_count + l];
    out[l].position = a.position + s.alpha * (b.position - a.position);
    out[l].towards = a.towards + s.alpha * (b.towards - a.towards);
  }
}

}  // namespace kinray
