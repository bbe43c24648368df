#include "scenes/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "scenes/camera_space.h"
#include "util/input_error.h"

namespace kinray {

Color Texture::sample(Vec2f uv) const {
  if (width <= 0 || height <= 0) return Color::Ones();
  const float x = (uv.x() - std::floor(uv.x())) * float(width) - 0.5f;
  const float y = (1.0f - (uv.y() - std::floor(uv.y()))) * float(height) - 0.5f;
  const float fx = std::floor(x), fy = std::floor(y);
  return blend((long long)fx, (long long)fy, x - fx, y - fy);
}

Color Texture::blend(long long i, long long j, float ax, float ay) const {
  auto texel = [&](long long a, long long b) -> const Color& {
    a = ((a % width) + width) % width;
    b = ((b % height) + height) % height;
    return texels[size_t(b) * size_t(width) + size_t(a)];
  };
  return (1 - ay) * ((1 - ax) * texel(i, j) + ax * texel(i + 1, j)) +
         ay * ((1 - ax) * texel(i, j + 1) + ax * texel(i + 1, j + 1));
}

Vec3 RigidKeys::transform(const Eigen::Affine3d& m, const Vec3& p) {
  return m * p;
}

std::vector<Vec3> Object::key_vertices(size_t k) const {
  if (!rigid) return key_positions[k];
  std::vector<Vec3> out(vertex_count());
  for (uint32_t v = 0; v < out.size(); ++v) out[v] = key_position(k, v);
  return out;
}

void Object::make_keys_explicit() {
  if (!rigid) return;
  key_positions.resize(key_position_sets());
  for (size_t k = 0; k < key_positions.size(); ++k) key_positions[k] = key_vertices(k);
  rigid.reset();
}

bool Object::is_static() const {
  if (rigid) {
    // Equal transforms place every vertex alike; different ones may still (a spin about an axis
    // through every vertex), so only then are the positions compared.
    const std::vector<Eigen::Affine3d>& transforms = *rigid->transforms;
    for (size_t k = 1; k < transforms.size(); ++k) {
      if (transforms[k].matrix() == transforms[0].matrix()) continue;
      for (uint32_t v = 0; v < vertex_count(); ++v)
        if (key_position(k, v) != key_position(0, v)) return false;
    }
    return true;
  }
  for (size_t k = 1; k < key_positions.size(); ++k)
    if (key_positions[k] != key_positions[0]) return false;
  return true;
}

void Object::set_flightplans(std::vector<double> times, std::vector<std::vector<Vec3>> positions) {
  Object candidate = *this;
  candidate.key_times = std::move(times);
  candidate.key_positions = std::move(positions);
  candidate.rigid.reset();
  Scene probe;
  probe.objects.push_back(candidate);
  probe.materials.resize(candidate.material + 1);
  probe.validate("flightplan update of '" + name + "'");
  *this = std::move(candidate);
}

Vec3 Object::position(uint32_t v, double t) const {
  const KeySegment s = locate(key_times, t);
  if (key_times.size() < 2) return key_position(0, v);
  const Vec3 a = key_position(s.k, v);
  const Vec3 b = key_position(s.k + 1, v);
  return a + s.alpha * (b - a);
}

CameraKey Camera::at(double t) const {
  std::vector<double> times(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) times[k] = keys[k].time;
  if (keys.size() < 2) return keys.front();
  const KeySegment s = locate(times, t);
  const CameraKey& a = keys[s.k];
  const CameraKey& b = keys[s.k + 1];
  CameraKey key;
  key.time = t;
  key.position = a.position + s.alpha * (b.position - a.position);
  key.orientation = a.orientation.slerp(s.alpha, b.orientation);
  key.fov_y_degrees = a.fov_y_degrees + s.alpha * (b.fov_y_degrees - a.fov_y_degrees);
  return key;
}

CameraKey Camera::look_at(double time, const Vec3& eye, const Vec3& target, const Vec3& up,
                          double fov_y_degrees) {
  // Stored as the usual right-handed camera frame (right, up, back); camera space of docs/design.md
  // looks down +z, which camera_space.cpp gets by negating z.
  const Vec3 forward = (target - eye).normalized();
  Vec3 right = forward.cross(up);
  if (right.squaredNorm() < 1e-20) right = forward.cross(Vec3::UnitX().cross(forward).norm() > 1e-6 ? Vec3::UnitX() : Vec3::UnitZ());
  right.normalize();
  const Vec3 true_up = right.cross(forward);
  Eigen::Matrix3d rotation;
  rotation.col(0) = right;
  rotation.col(1) = true_up;
  rotation.col(2) = -forward;
  CameraKey key;
  key.time = time;
  key.position = eye;
  key.orientation = Eigen::Quaterniond(rotation).normalized();
  key.fov_y_degrees = fov_y_degrees;
  return key;
}

namespace {

void check_times(const std::vector<double>& times, const std::string& where) {
  if (times.empty()) throw InputError(where, "no key times");
  for (size_t k = 0; k < times.size(); ++k) {
    if (!std::isfinite(times[k]))
      throw InputError(where, "key time " + std::to_string(k) + " is not a finite number");
    if (std::abs(times[k]) > kMaxTime) {
      std::ostringstream message;
      message << "key time " << k << " (t=" << times[k] << ") lies beyond +-1e9 s";
      throw InputError(where, message.str());
    }
    if (k > 0 && !(times[k] > times[k - 1])) {
      std::ostringstream message;
      message << "key times must be strictly increasing, but key " << k << " (t=" << times[k]
              << ") follows t=" << times[k - 1] << (times[k] == times[k - 1] ? " (duplicate)" : " (unsorted)");
      throw InputError(where, message.str());
    }
    if (k > 0 && times[k] - times[k - 1] < kMinKeySpacing) {
      std::ostringstream message;
      message << "keys " << k - 1 << " and " << k << " are " << times[k] - times[k - 1]
              << " s apart; keys must be at least 1e-9 s apart";
      throw InputError(where, message.str());
    }
  }
}

}  // namespace

namespace {

std::string describe_far(const Vec3& p) {
  char text[96];
  std::snprintf(text, sizeof text, "%g, %g, %g", p.x(), p.y(), p.z());
  return text;
}

}  // namespace

std::optional<std::string> light_problem(const Light& light) {
  if (light.kind == Light::Kind::point) {
    if (!light.position.allFinite()) return "the position is NaN or infinite";
    if (light.position.cwiseAbs().maxCoeff() > kMaxCoordinate)
      return "the position has a coordinate beyond +-1e15 (" + describe_far(light.position) +
             "), which the float references cannot trace";
  } else if (!light.direction.allFinite() || !(light.direction.norm() > 0)) {
    return "the direction must be finite and not zero";
  }
  if (!light.color.allFinite() || (light.color.array() < 0).any())
    return "the colour must be finite (as a float) and >= 0";
  return std::nullopt;
}

void Scene::validate(const std::string& source) const {
  if (!std::isfinite(time_begin) || !std::isfinite(time_end) || !(time_end > time_begin))
    throw InputError(source, "the shot must have finite times with end > begin, got [" +
                                 std::to_string(time_begin) + ", " + std::to_string(time_end) + "]");
  if (std::abs(time_begin) > kMaxTime || std::abs(time_end) > kMaxTime ||
      time_end - time_begin < kMinKeySpacing) {
    std::ostringstream message;
    message << "the shot [" << time_begin << ", " << time_end
            << "] must lie within +-1e9 s and last at least 1e-9 s";
    throw InputError(source, message.str());
  }
  if (materials.empty()) throw InputError(source, "no materials");
  for (size_t m = 0; m < materials.size(); ++m) {
    const Color& c = materials[m].base_color;
    if (!c.allFinite() || (c.array() < 0).any())
      throw InputError(source, "material " + std::to_string(m) + " has an invalid base colour");
    if (materials[m].texture >= int(textures.size()))
      throw InputError(source, "material " + std::to_string(m) + " names a missing texture");
  }
  for (size_t o = 0; o < objects.size(); ++o) {
    const Object& object = objects[o];
    const std::string where = source + ": object " + std::to_string(o) +
                              (object.name.empty() ? "" : " '" + object.name + "'");
    check_times(object.key_times, where);
    if (object.key_position_sets() != object.key_times.size())
      throw InputError(where, std::to_string(object.key_times.size()) + " key times but " +
                                  std::to_string(object.key_position_sets()) +
                                  " key position sets");
    const size_t nv = object.vertex_count();
    for (size_t k = 0; k < object.key_position_sets(); ++k) {
      if (!object.rigid && object.key_positions[k].size() != nv)
        throw InputError(where, "key " + std::to_string(k) + " has " +
                                    std::to_string(object.key_positions[k].size()) +
                                    " vertices, key 0 has " + std::to_string(nv));
      for (uint32_t v = 0; v < nv; ++v) {
        const Vec3 p = object.key_position(k, v);
        if (!p.allFinite())
          throw InputError(where, "vertex " + std::to_string(v) + " at key " + std::to_string(k) +
                                      " is NaN or infinite");
        if (p.cwiseAbs().maxCoeff() > kMaxCoordinate)
          throw InputError(where, "vertex " + std::to_string(v) + " at key " + std::to_string(k) +
                                      " has a coordinate beyond +-1e15 (" + describe_far(p) +
                                      "), which the float references cannot trace");
      }
    }
    for (size_t f = 0; f < object.triangles.size(); ++f)
      for (uint32_t index : object.triangles[f])
        if (index >= nv)
          throw InputError(where, "triangle " + std::to_string(f) + " has vertex index " +
                                      std::to_string(index) + " out of range (" +
                                      std::to_string(nv) + " vertices)");
    if (!object.uvs.empty() && object.uvs.size() != nv)
      throw InputError(where, "has " + std::to_string(object.uvs.size()) + " uvs for " +
                                  std::to_string(nv) + " vertices");
    for (size_t v = 0; v < object.uvs.size(); ++v)
      if (!object.uvs[v].allFinite())
        throw InputError(where, "the texture coordinates of vertex " + std::to_string(v) +
                                    " are NaN or infinite");
    if (object.material >= materials.size())
      throw InputError(where, "material index " + std::to_string(object.material) + " out of range");
    if (std::isnan(object.appear) || std::isnan(object.disappear) || !(object.disappear > object.appear))
      throw InputError(where, "must disappear after it appears");
  }
  std::vector<double> camera_times;
  for (const CameraKey& key : camera.keys) {
    camera_times.push_back(key.time);
    if (!key.position.allFinite() || !key.orientation.coeffs().allFinite())
      throw InputError(source + ": camera", "a key has a NaN or infinite position or orientation");
    if (key.position.cwiseAbs().maxCoeff() > kMaxCoordinate)
      throw InputError(source + ": camera", "a key's position has a coordinate beyond +-1e15 (" +
                                                describe_far(key.position) +
                                                "), which the float references cannot trace");
    if (!(key.fov_y_degrees > 0.5 && key.fov_y_degrees < 179.5))
      throw InputError(source + ": camera", "fov_y must lie in (0.5, 179.5) degrees, got " +
                                                std::to_string(key.fov_y_degrees));
  }
  check_times(camera_times, source + ": camera");
  for (size_t l = 0; l < lights.size(); ++l)
    if (const std::optional<std::string> problem = light_problem(lights[l]))
      throw InputError(source + ": light " + std::to_string(l), *problem);
}

std::vector<double> Scene::key_times() const {
  std::vector<double> times = {time_begin, time_end};
  auto add = [&](double t) {
    if (t > time_begin && t < time_end) times.push_back(t);
  };
  for (const Object& object : objects) {
    if (object.is_static()) continue;
    for (double t : object.key_times) add(t);
  }
  if (camera.keys.size() > 1)
    for (const CameraKey& key : camera.keys) add(key.time);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

size_t Scene::triangle_count() const {
  size_t n = 0;
  for (const Object& object : objects) n += object.triangles.size();
  return n;
}

size_t Scene::vertex_count() const {
  size_t n = 0;
  for (const Object& object : objects) n += object.vertex_count();
  return n;
}

Eigen::AlignedBox3d Scene::bounds() const {
  Eigen::AlignedBox3d box;
  for (const Object& object : objects)
    for (size_t k = 0; k < object.key_position_sets(); ++k)
      for (uint32_t v = 0; v < object.vertex_count(); ++v) box.extend(object.key_position(k, v));
  return box;
}

}  // namespace kinray
