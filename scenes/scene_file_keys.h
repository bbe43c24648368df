#pragma once
// The transform keys of a JSON scene file's objects: translation, rotation and scale keys (TRS),
// a static transform, resampling at a keyrate, and their application to an object's own vertex
// keys. Flightplans are linear between keys, so rotations are resampled finely to stay round.
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "scenes/camera_space.h"
#include "scenes/json_node.h"
#include "scenes/scene.h"

namespace kinray {

/// Translation, rotation and scale: vertices are scaled, then rotated, then translated.
struct Trs {
  Vec3 translation = Vec3::Zero();
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Vec3 scale = Vec3::Ones();

  [[nodiscard]] Eigen::Affine3d matrix() const {
    return Eigen::Translation3d(translation) * rotation * Eigen::Scaling(scale);
  }
  [[nodiscard]] static Trs blend(const Trs& a, const Trs& b, double alpha) {
    return {a.translation + alpha * (b.translation - a.translation),
            a.rotation.slerp(alpha, b.rotation), a.scale + alpha * (b.scale - a.scale)};
  }
};

/// Where an object stands over time: an optional static transform (applied first, so that TRS
/// keys can, say, rotate an object placed off-centre about the origin: an orbit), then TRS keys.
struct Placement {
  std::optional<Eigen::Affine3d> rest;
  std::vector<double> times;
  std::vector<Trs> keys;  ///< one per time

  [[nodiscard]] Trs at(double t) const {
    if (keys.size() == 1) return keys[0];
    const auto segment = locate(times, t);
    return Trs::blend(keys[segment.k], keys[segment.k + 1], segment.alpha);
  }
};

/// A rotation as a quaternion [w, x, y, z] (normalised; a unit one kept bit for bit).
[[nodiscard]] Eigen::Quaterniond parse_quaternion(const JsonNode& node);
/// A key's "time": finite and later than the previous key's.
[[nodiscard]] double parse_key_time(const JsonNode& key, std::optional<double> previous);
/// `times` refined to at least `keyrate` keys per second between the first and last, keeping the
/// originals.
[[nodiscard]] std::vector<double> resample(const std::vector<double>& times, double keyrate,
                                           const JsonNode& where);
/// An object's "transform" and, when `keys_are_transforms`, its TRS "keys" and "keyrate".
[[nodiscard]] Placement parse_placement(const JsonNode& object, bool keys_are_transforms);
/// Moves `object` by `placement`: the static transform applies to every key; TRS keys combine with
/// the object's own keys on the union of both key grids.
void apply_placement(Object& object, const Placement& placement);

}  // namespace kinray
