#include "scenes/scene_file_keys.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace kinray {
namespace {

// Guards against files that would exhaust memory rather than describe a scene.
constexpr double kMaxResampledKeys = 1e5;

}  // namespace

Eigen::Quaterniond parse_quaternion(const JsonNode& node) {
  node.expect_size(4);
  const Eigen::Quaterniond q(node[0].number(), node[1].number(), node[2].number(),
                             node[3].number());
  const double norm = q.norm();
  if (!(norm > 1e-12)) node.fail("a rotation quaternion [w, x, y, z] must not be zero");
  // Keep an already unit quaternion bit for bit, so that files written by save_scene_file
  // round-trip.
  return std::abs(norm - 1) < 1e-12 ? q : q.normalized();
}

namespace {

Eigen::Quaterniond parse_rotation(const JsonNode& node) {
  if (node.value().is_array()) return parse_quaternion(node);
  node.expect_object({"axis", "degrees"});
  const Vec3 axis = node.at("axis").vec3();
  if (!(axis.norm() > 1e-12)) node.at("axis").fail("the rotation axis must not be zero");
  return Eigen::Quaterniond(
      Eigen::AngleAxisd(node.at("degrees").number() * M_PI / 180, axis.normalized()));
}

Trs parse_trs(const JsonNode& node) {
  Trs trs;
  if (auto translation = node.find("translation")) trs.translation = translation->vec3();
  if (auto rotation = node.find("rotation")) trs.rotation = parse_rotation(*rotation);
  if (auto scale = node.find("scale")) {
    trs.scale = scale->value().is_array() ? scale->vec3() : Vec3::Constant(scale->number());
    if (!(trs.scale.array() != 0).all()) scale->fail("a scale must not be zero");
  }
  return trs;
}

}  // namespace

/// Checks that a key's time is finite and later than the previous key's.
double parse_key_time(const JsonNode& key, std::optional<double> previous) {
  const JsonNode time = key.at("time");
  const double t = time.number();
  if (previous && !(t > *previous)) {
    std::ostringstream message;
    message << "key times must be strictly increasing, but t=" << t << " follows t=" << *previous
            << (t == *previous ? " (duplicate)" : " (unsorted)");
    time.fail(message.str());
  }
  return t;
}

/// `times` refined to at least `keyrate` keys per second between the first and last, keeping the
/// originals: the flightplans are linear between keys, so rotations need fine keys to stay round.
std::vector<double> resample(const std::vector<double>& times, double keyrate, const JsonNode& where) {
  if (keyrate <= 0 || times.size() < 2) return times;
  const double span = times.back() - times.front();
  if (span * keyrate > kMaxResampledKeys)
    where.fail("resampling at this keyrate would make more than " +
               std::to_string(int(kMaxResampledKeys)) + " keys");
  std::vector<double> result = times;
  const size_t intervals = size_t(std::ceil(span * keyrate - 1e-9));
  for (size_t k = 1; k < intervals; ++k)
    result.push_back(times.front() + span * double(k) / double(intervals));
  std::sort(result.begin(), result.end());
  // Merge near-coincident times (a grid time a hair from an original key) into the original.
  std::vector<double> merged;
  for (double t : result)
    if (merged.empty() || t - merged.back() > 1e-9 * std::max(1.0, span))
      merged.push_back(t);
    else if (std::find(times.begin(), times.end(), t) != times.end())
      merged.back() = t;
  return merged;
}

/// Reads an object's "transform" and, when `keys_are_transforms`, its TRS "keys" and "keyrate".
Placement parse_placement(const JsonNode& object, bool keys_are_transforms) {
  Placement placement;
  if (auto transform = object.find("transform")) {
    transform->expect_object({"translation", "rotation", "scale"});
    placement.rest = parse_trs(*transform).matrix();
  }
  const auto keys = keys_are_transforms ? object.find("keys") : std::nullopt;
  if (!keys) return placement;
  if (keys->size() == 0) keys->fail("expected at least one key");
  std::optional<double> previous;
  for (size_t k = 0; k < keys->size(); ++k) {
    const JsonNode key = (*keys)[k];
    key.expect_object({"time", "translation", "rotation", "scale"});
    previous = parse_key_time(key, previous);
    placement.times.push_back(*previous);
    placement.keys.push_back(parse_trs(key));
  }
  if (auto keyrate = object.find("keyrate")) {
    const double rate = keyrate->positive();
    const Placement coarse = placement;
    placement.times = resample(coarse.times, rate, *keyrate);
    placement.keys.clear();
    for (double t : placement.times) placement.keys.push_back(coarse.at(t));
  }
  return placement;
}

/// Moves `object` by `placement`: the static transform applies to every key; TRS keys combine with
/// the object's own keys on the union of both key grids.
void apply_placement(Object& object, const Placement& placement) {
  object.make_keys_explicit();
  if (placement.rest)
    for (auto& key : object.key_positions)
      for (Vec3& p : key) p = *placement.rest * p;
  if (placement.keys.empty()) return;
  std::vector<double> times = placement.times;
  if (object.key_count() > 1)
    times.insert(times.end(), object.key_times.begin(), object.key_times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  std::vector<std::vector<Vec3>> positions(times.size(), std::vector<Vec3>(object.vertex_count()));
  for (size_t k = 0; k < times.size(); ++k) {
    const Eigen::Affine3d matrix = placement.at(times[k]).matrix();
    for (uint32_t v = 0; v < object.vertex_count(); ++v)
      positions[k][v] = matrix * object.position(v, times[k]);
  }
  object.key_times = std::move(times);
  object.key_positions = std::move(positions);
}

}  // namespace kinray
