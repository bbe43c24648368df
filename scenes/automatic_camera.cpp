#include "scenes/automatic_camera.h"

#include <algorithm>
#include <cmath>
#include <span>

#include "scenes/camera_space.h"
#include "util/parallel.h"

namespace kinray {
namespace {

/// The camera key that looks at `centre` from the framing direction, far enough that a sphere of
/// `radius` around it fits in the vertical (and so, on wide images, the horizontal) field of view.
CameraKey look_from_framing_direction(const FramingConfig& config, const Vec3& centre,
                                      double radius, double time) {
  if (!(radius > 0)) radius = 1;  // a point (or nothing) is shown from a unit distance
  const double half_fov = config.fov_y_degrees * M_PI / 360;
  const double distance = config.margin * radius / std::sin(half_fov);
  const double elevation = config.elevation_degrees * M_PI / 180;
  const Vec3 direction(0, std::sin(elevation), std::cos(elevation));
  return Camera::look_at(time, centre + distance * direction, centre, Vec3::UnitY(),
                         config.fov_y_degrees);
}

/// Key times of the moving objects inside [begin, end] clipped to the shot, and its ends.
std::vector<double> object_key_times(const Scene& scene, double begin, double end) {
  double first = std::max(scene.time_begin, begin), last = std::min(scene.time_end, end);
  if (!(first <= last)) first = scene.time_begin, last = scene.time_end;
  std::vector<double> times = {first, last};
  for (const Object& object : scene.objects)
    if (object.key_count() > 1 && !object.is_static())
      for (double t : object.key_times)
        if (t > first && t < last) times.push_back(t);
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

/// The centre path averaged over a window of `width` seconds: the box filter of the
/// piecewise-linear path through `centres`, integrated exactly.
std::vector<Vec3> smoothed_path(std::span<const double> times, std::span<const Vec3> centres,
                                double width) {
  const size_t n = times.size();
  std::vector<Vec3> prefix(n, Vec3::Zero());  // integral of the path from times[0] to times[k]
  for (size_t k = 1; k < n; ++k)
    prefix[k] = prefix[k - 1] + 0.5 * (times[k] - times[k - 1]) * (centres[k - 1] + centres[k]);
  const auto integral = [&](double t) -> Vec3 {
    const KeySegment s = locate(times, t);
    if (n < 2) return Vec3::Zero();
    const Vec3 at_t = centres[s.k] + s.alpha * (centres[s.k + 1] - centres[s.k]);
    return prefix[s.k] + 0.5 * (s.alpha * (times[s.k + 1] - times[s.k])) * (centres[s.k] + at_t);
  };
  std::vector<Vec3> smoothed(n);
  for (size_t k = 0; k < n; ++k) {
    // A window centred on the key, narrowed near the shot's ends so that it stays centred: a
    // subject moving at constant velocity is looked at exactly.
    const double half = std::min({width / 2, times[k] - times.front(), times.back() - times[k]});
    smoothed[k] = half > 0
                      ? Vec3((integral(times[k] + half) - integral(times[k] - half)) / (2 * half))
                      : centres[k];
  }
  return smoothed;
}

}  // namespace

std::vector<FramedKey> framed_keys(const Scene& scene, double begin, double end) {
  const std::vector<double> times = object_key_times(scene, begin, end);
  std::vector<FramedKey> keys(times.size());
  parallel_for(times.size(), 0, [&](size_t k) {
    const double before = times[k == 0 ? 0 : k - 1],
                 after = times[std::min(k + 1, times.size() - 1)];
    keys[k].time = times[k];
    for (const Object& object : scene.objects) {
      if (!(object.appear <= after && object.disappear > before)) continue;
      const KeySegment s = locate(object.key_times, times[k]);
      const uint32_t nv = uint32_t(object.vertex_count());
      if (object.key_count() < 2 || s.alpha == 0) {
        for (uint32_t v = 0; v < nv; ++v) keys[k].bounds.extend(object.key_position(s.k, v));
        continue;
      }
      for (uint32_t v = 0; v < nv; ++v) {
        const Vec3 a = object.key_position(s.k, v), b = object.key_position(s.k + 1, v);
        keys[k].bounds.extend(Vec3(a + s.alpha * (b - a)));
      }
    }
  });
  return keys;
}

Camera automatic_camera(const Scene& scene, const FramingConfig& config) {
  const std::vector<FramedKey> keys = framed_keys(scene, config.begin, config.end);
  Eigen::AlignedBox3d shown;
  bool every_key_shows_something = true;
  for (const FramedKey& key : keys) {
    shown.extend(key.bounds);
    every_key_shows_something = every_key_shows_something && !key.bounds.isEmpty();
  }
  const Vec3 shown_centre = shown.isEmpty() ? Vec3(Vec3::Zero()) : Vec3(shown.center());
  const double still_radius = shown.isEmpty() ? 0.0 : 0.5 * shown.diagonal().norm();
  Camera still;
  still.keys = {look_from_framing_direction(config, shown_centre, still_radius, keys.front().time)};
  if (keys.size() < 2 || !every_key_shows_something) return still;

  std::vector<double> times(keys.size());
  std::vector<Vec3> centres(keys.size());
  for (size_t k = 0; k < keys.size(); ++k) {
    times[k] = keys[k].time;
    centres[k] = keys[k].bounds.center();
  }
  const std::vector<Vec3> path = smoothed_path(times, centres, config.smoothing_seconds);
  // The sphere around the smoothed centre that holds the subject's bounds at every key.
  double follow_radius = 0;
  for (size_t k = 0; k < keys.size(); ++k)
    follow_radius = std::max(
        follow_radius, (centres[k] - path[k]).norm() + 0.5 * keys[k].bounds.diagonal().norm());
  if (still_radius <= config.follow_gain * follow_radius) return still;
  Camera follow;
  follow.keys.clear();
  for (size_t k = 0; k < keys.size(); ++k)
    follow.keys.push_back(look_from_framing_direction(config, path[k], follow_radius, times[k]));
  return follow;
}

void frame_automatically(Scene& scene, const std::string& reason, const FramingConfig& config) {
  scene.camera = automatic_camera(scene, config);
  scene.camera_source = {CameraSource::Kind::automatic, "", reason};
}

}  // namespace kinray
