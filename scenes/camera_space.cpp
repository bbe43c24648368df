#include "scenes/camera_space.h"

#include <algorithm>
#include <cmath>

#include "util/parallel.h"

namespace kinray {

KeySegment locate(std::span<const double> key_times, double t) {
  const size_t n = key_times.size();
  if (n < 2 || t <= key_times[0]) return {0, 0.0};
  if (t >= key_times[n - 1]) return {n - 2, 1.0};
  const size_t k = size_t(std::upper_bound(key_times.begin(), key_times.end(), t) - key_times.begin()) - 1;
  return {k, (t - key_times[k]) / (key_times[k + 1] - key_times[k])};
}

KeySegment locate(std::span<const double> key_times, double t, size_t next) {
  if (next > 0 && next < key_times.size() && key_times[next - 1] < t && t < key_times[next])
    return {next - 1, (t - key_times[next - 1]) / (key_times[next] - key_times[next - 1])};
  return locate(key_times, t);
}

Vec3 CameraSpaceObject::position(uint32_t v, double t) const {
  if (key_times.size() < 2) return positions[v];
  return position(v, locate(key_times, t));
}

Vec3 CameraSpaceObject::position(uint32_t v, const KeySegment& s) const {
  if (key_times.size() < 2) return positions[v];
  const Vec3& a = positions[s.k * vertex_count + v];
  const Vec3& b = positions[(s.k + 1) * vertex_count + v];
  return a + s.alpha * (b - a);
}

Eigen::Vector3f CameraSpaceObject::normal(uint32_t v, double t) const {
  if (key_times.size() < 2) return normals[v];
  return normal(v, locate(key_times, t));
}

Eigen::Vector3f CameraSpaceObject::normal(uint32_t v, const KeySegment& s) const {
  if (key_times.size() < 2) return normals[v];
  const Eigen::Vector3f& a = normals[s.k * vertex_count + v];
  const Eigen::Vector3f& b = normals[(s.k + 1) * vertex_count + v];
  return a + float(s.alpha) * (b - a);
}

void CameraSpaceObject::positions_at(double t, std::vector<Vec3>& out) const {
  out.resize(vertex_count);
  if (key_times.size() < 2) {
    std::copy(positions.begin(), positions.begin() + vertex_count, out.begin());
    return;
  }
  const KeySegment s = locate(key_times, t);
  const Vec3* a = positions.data() + s.k * vertex_count;
  const Vec3* b = a + vertex_count;
  for (size_t v = 0; v < vertex_count; ++v) out[v] = a[v] + s.alpha * (b[v] - a[v]);
}

namespace {

/// World to true camera space (x right, y up, looking down +z) for one camera key.
struct CameraTransform {
  Eigen::Matrix3d world_to_camera;
  Vec3 eye;
  double fov_scale;  ///< 1 / tan(fov_y / 2)
  explicit CameraTransform(const CameraKey& key) : eye(key.position) {
    world_to_camera = key.orientation.normalized().toRotationMatrix().transpose();
    world_to_camera.row(2) *= -1.0;  // the stored frame looks down -z; camera space looks down +z
    fov_scale = 1.0 / std::tan(key.fov_y_degrees * M_PI / 360.0);
  }
  [[nodiscard]] Vec3 to_camera(const Vec3& p) const { return world_to_camera * (p - eye); }
};

void vertex_normals(std::span<const Vec3> true_positions, const std::vector<Triangle>& triangles,
                    Eigen::Vector3f* out) {
  std::vector<Vec3> sum(true_positions.size(), Vec3::Zero());
  for (const Triangle& tri : triangles) {
    const Vec3 n = (true_positions[tri[1]] - true_positions[tri[0]])
                       .cross(true_positions[tri[2]] - true_positions[tri[0]]);
    for (uint32_t v : tri) sum[v] += n;
  }
  for (size_t v = 0; v < sum.size(); ++v) {
    const double length = sum[v].norm();
    out[v] = length > 0 ? (sum[v] / length).cast<float>() : Eigen::Vector3f(0, 0, -1);
  }
}

}  // namespace

namespace {

/// Drops the keys outside what `span` needs: the last key at or before its start and the first at
/// or after its end bound it; locate() finds the same segment and alpha inside it.
void keep_keys_of(std::vector<double>& key_times, const std::pair<double, double>& span) {
  const auto first = std::upper_bound(key_times.begin(), key_times.end(), span.first);
  const auto last = std::lower_bound(key_times.begin(), key_times.end(), span.second);
  const size_t begin = first == key_times.begin() ? 0 : size_t(first - key_times.begin()) - 1;
  const size_t end =
      last == key_times.end() ? key_times.size() : size_t(last - key_times.begin()) + 1;
  key_times = std::vector<double>(key_times.begin() + std::ptrdiff_t(begin),
                                  key_times.begin() + std::ptrdiff_t(end));
}

/// camera_space_key_times of `object`, whose motion (`moves`: !is_static()) is known.
std::vector<double> key_times_of(const Scene& scene, const Object& object, bool moves,
                                 const std::optional<std::pair<double, double>>& span) {
  std::vector<double> key_times;
  if (moves) key_times = object.key_times;
  if (scene.camera.keys.size() > 1)
    for (const CameraKey& key : scene.camera.keys) key_times.push_back(key.time);
  if (key_times.empty()) key_times.push_back(object.key_times.front());
  std::sort(key_times.begin(), key_times.end());
  key_times.erase(std::unique(key_times.begin(), key_times.end()), key_times.end());
  if (span) keep_keys_of(key_times, *span);
  return key_times;
}

}  // namespace

std::vector<double> camera_space_key_times(const Scene& scene, size_t o,
                                           std::optional<std::pair<double, double>> span) {
  const Object& object = scene.objects[o];
  return key_times_of(scene, object, !object.is_static(), span);
}

CameraSpaceScene CameraSpaceScene::build(const Scene& scene,
                                         std::optional<std::pair<double, double>> span) {
  CameraSpaceScene result;
  result.scene = &scene;
  result.objects.resize(scene.objects.size());
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    CameraSpaceObject& cs = result.objects[o];
    cs.object = uint32_t(o);
    cs.vertex_count = object.vertex_count();
    cs.appear = object.appear;
    cs.disappear = object.disappear;
    const bool object_moves = !object.is_static();
    cs.key_times = key_times_of(scene, object, object_moves, span);

    const size_t nk = cs.key_times.size(), nv = cs.vertex_count;
    cs.positions.resize(nk * nv);
    cs.normals.resize(nk * nv);
    parallel_for(nk, 0, [&](size_t k) {
      const double t = cs.key_times[k];
      const CameraTransform camera(scene.camera.at(t));
      std::vector<Vec3> true_positions(nv);
      for (uint32_t v = 0; v < nv; ++v)
        true_positions[v] =
            camera.to_camera(object_moves ? object.position(v, t) : object.key_position(0, v));
      vertex_normals(true_positions, object.triangles, cs.normals.data() + k * nv);
      for (size_t v = 0; v < nv; ++v) {
        const Vec3& p = true_positions[v];
        cs.positions[k * nv + v] = Vec3(p.x() * camera.fov_scale, p.y() * camera.fov_scale, p.z());
      }
    });
    cs.is_static = nk == 1;
  }
  for (const CameraKey& key : scene.camera.keys) {
    result.camera_key_times.push_back(key.time);
    result.camera_fov_y.push_back(key.fov_y_degrees);
  }
  result.fixed_tan = result.fixed_tan_half_fov();
  return result;
}

double CameraSpaceScene::tan_half_fov(double t) const {
  if (fixed_tan) return *fixed_tan;
  // Camera::at's interpolation of the fov, without building the whole key.
  if (camera_fov_y.empty()) return std::tan(scene->camera.at(t).fov_y_degrees * M_PI / 360.0);
  double fov_y = camera_fov_y.front();
  if (camera_fov_y.size() >= 2) {
    const KeySegment s = locate(camera_key_times, t);
    fov_y = camera_fov_y[s.k] + s.alpha * (camera_fov_y[s.k + 1] - camera_fov_y[s.k]);
  }
  return std::tan(fov_y * M_PI / 360.0);
}

std::optional<double> CameraSpaceScene::fixed_tan_half_fov() const {
  const auto& fov = camera_fov_y;
  if (fov.empty() || !std::all_of(fov.begin(), fov.end(), [&](double f) { return f == fov[0]; }))
    return std::nullopt;
  return tan_half_fov(camera_key_times.front());
}

size_t CameraSpaceScene::triangle_count() const { return scene->triangle_count(); }

}  // namespace kinray
