#pragma once
// Camera space (docs/design.md): every backend consumes the scene as camera-space flightplans.
// Keyframe positions are transformed into camera space at each key (the union of the object's and
// the camera's key times) and interpolated linearly there, so an animated camera keeps the relative
// motion piecewise linear. The field of view is folded into the positions (x and y scaled by 1 /
// tan(fov_y / 2)), so the pixel-centre rays d_ij = (x_i, y_j, 1) never change, even when the fov is
// animated; the ray parameter of a hit is still the camera-space depth z.
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "scenes/scene.h"
#include "util/pixel_rays.h"

namespace kinray {

/// Where t falls on a key grid: segment k (between keys k and k+1) and the fraction alpha in
/// [0, 1]. Outside the grid the motion stands still (k clamps, alpha is 0 or 1).
struct KeySegment {
  size_t k = 0;
  double alpha = 0;
};
[[nodiscard]] KeySegment locate(std::span<const double> key_times, double t);
/// locate(key_times, t) for a t already known to lie in [key_times[next - 1], key_times[next]]
/// (next = 0 or the key count: before or after them): without the search where t lies strictly
/// inside, else by the search. The same segment and alpha, bit for bit.
[[nodiscard]] KeySegment locate(std::span<const double> key_times, double t, size_t next);

/// The key times of object o's camera-space flightplans (CameraSpaceScene::build): its own if it
/// moves and the camera's if that moves (else its first), only those that `span` needs.
[[nodiscard]] std::vector<double> camera_space_key_times(
    const Scene& scene, size_t o, std::optional<std::pair<double, double>> span = std::nullopt);

/// One object's camera-space flightplans.
struct CameraSpaceObject {
  uint32_t object = 0;              ///< index into Scene::objects; the id in ID buffers
  std::vector<double> key_times;    ///< strictly increasing, at least one
  std::vector<Vec3> positions;      ///< [key * vertex_count + v], fov-normalized camera space
  std::vector<Eigen::Vector3f> normals;  ///< [key * vertex_count + v], unit, true camera space
  size_t vertex_count = 0;
  bool is_static = false;           ///< camera-space positions equal at every key
  double appear = -kInfinity, disappear = kInfinity;

  [[nodiscard]] std::span<const Vec3> key(size_t k) const {
    return {positions.data() + k * vertex_count, vertex_count};
  }
  [[nodiscard]] bool visible(double t) const { return t >= appear && t < disappear; }
  [[nodiscard]] Vec3 position(uint32_t v, double t) const;
  [[nodiscard]] Eigen::Vector3f normal(uint32_t v, double t) const;
  /// The same at a time already located on key_times (one search for many vertices).
  [[nodiscard]] Vec3 position(uint32_t v, const KeySegment& s) const;
  [[nodiscard]] Eigen::Vector3f normal(uint32_t v, const KeySegment& s) const;
  /// All positions at t, into `out` (resized).
  void positions_at(double t, std::vector<Vec3>& out) const;
};

/// The whole scene in camera space: what the kinetic, Embree and OSMesa backends all consume,
/// so that the three agree bit for bit up to ties.
struct CameraSpaceScene {
  const Scene* scene = nullptr;
  std::vector<CameraSpaceObject> objects;  ///< one per Scene::objects entry, same order

  std::vector<double> camera_key_times;  ///< the camera's key times, for tan_half_fov
  std::vector<double> camera_fov_y;      ///< the camera's fov_y_degrees at its keys
  /// fixed_tan_half_fov(), kept by build: tan_half_fov's answer without a search and a tan, for
  /// the shading's many calls.
  std::optional<double> fixed_tan;

  /// Builds camera-space flightplans from `scene`, which must outlive the result. With a
  /// `span` [a, b], each object keeps only the keys that positions inside it need (from the last
  /// key at or before a to the first at or after b), the same bits there as with every key: a
  /// short shot of a long animation (BART robots, 800 keys) holds a few keys, not all.
  static CameraSpaceScene build(const Scene& scene,
                                std::optional<std::pair<double, double>> span = std::nullopt);
  /// tan(fov_y / 2) of the camera at t: undoes the fov folding for shading (the fov of
  /// Camera::at(t), bit for bit, without its allocation and slerp: shading calls it per sample).
  [[nodiscard]] double tan_half_fov(double t) const;
  /// tan_half_fov(t) for every t when the fov is the same at every camera key (the
  /// interpolation a + alpha (a - a) is exactly a), else nothing.
  [[nodiscard]] std::optional<double> fixed_tan_half_fov() const;
  [[nodiscard]] size_t triangle_count() const;
  [[nodiscard]] const std::vector<Triangle>& triangles(size_t object) const {
    return scene->objects[object].triangles;
  }
};

}  // namespace kinray
