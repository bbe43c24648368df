#include "scenes/procedural.h"

#include <cmath>

#include "util/input_error.h"

namespace kinray {

const std::vector<BuiltinScene>& builtin_scenes() {
  static const std::vector<BuiltinScene> scenes = {
      {"wavy-sphere",
       "a slowly spinning sphere with travelling waves on its surface, fixed camera (default, "
       "benchmark)",
       {40000, 2, 24},
       &make_wavy_sphere},
      {"cloth",
       "a hanging cloth whose lower part curls up in front of, then behind, its upper part",
       {20000, 3, 24},
       &make_cloth},
      {"orbit",
       "spheres and boxes orbiting a central sphere, passing in front of each other and through it",
       {20000, 3, 24},
       &make_orbit},
      {"flythrough",
       "an animated camera (position, orientation, fov) flying between pillars and under lintels",
       {20000, 4, 24},
       &make_flythrough},
      {"static-moving",
       "static ground and wall, a bouncing ball, and a spinning box that appears and later "
       "disappears",
       {10000, 2, 24},
       &make_static_moving},
      {"cloth-fold",
       "a rippled sheet whose right half folds over onto and through its left half "
       "(self-collision)",
       {2000, 2, 24},
       &make_cloth_fold},
      {"crossing",
       "two wobbling spheres passing through each other (collision of deforming objects)",
       {2000, 2, 24},
       &make_crossing},
      {"glide",
       "two wobbling spheres gliding past each other, surfaces at least a gap apart (near misses; "
       "their bulges meet from about gap=-0.03)",
       {2000, 2, 24, 0.01},
       &make_glide},
      {"cloth-slide",
       "a flat cloth sliding over a still sphere that lifts it, a gap above it (near misses; the "
       "cloth's chords touch below about gap=0.008 at 2000 triangles)",
       {2000, 2, 24, 0.01},
       &make_cloth_slide},
      {"swing",
       "an arm of two links and a hand swinging like a double pendulum, the hand a gap above a "
       "floor at the bottom of each swing (near misses of an articulated body)",
       {2000, 2, 24, 0.01},
       &make_swing},
  };
  return scenes;
}

std::vector<std::string> builtin_scene_names() {
  std::vector<std::string> names;
  for (const BuiltinScene& scene : builtin_scenes()) names.push_back(scene.name);
  return names;
}

bool is_builtin_scene(const std::string& name) {
  for (const BuiltinScene& scene : builtin_scenes())
    if (scene.name == name) return true;
  return false;
}

ProceduralParams builtin_scene_params(const std::string& name,
                                      const std::map<std::string, double>& params) {
  const BuiltinScene* builtin = nullptr;
  for (const BuiltinScene& scene : builtin_scenes())
    if (scene.name == name) builtin = &scene;
  if (!builtin) {
    std::string valid;
    for (const std::string& n : builtin_scene_names()) valid += (valid.empty() ? "" : ", ") + n;
    throw InputError("scene '" + name + "'",
                     "unknown built-in scene; the built-in scenes are " + valid);
  }
  ProceduralParams values = builtin->defaults;
  const std::string where = "scene '" + name + "'";
  const bool takes_gap = values.gap.has_value();
  for (const auto& [key, value] : params) {
    if (key == "gap" && takes_gap) {
      if (!std::isfinite(value))
        throw InputError(where, "parameter gap must be finite, got " + std::to_string(value));
      values.gap = value;
      continue;
    }
    double* field = key == "triangles"  ? &values.triangles
                    : key == "duration" ? &values.duration
                    : key == "keyrate"  ? &values.keyrate
                                        : nullptr;
    if (!field)
      throw InputError(where, "unknown parameter '" + key +
                                  "'; the parameters are triangles, duration, keyrate" +
                                  (takes_gap ? ", gap" : ""));
    if (!std::isfinite(value) || !(value > 0))
      throw InputError(
          where, "parameter " + key + " must be a finite number > 0, got " + std::to_string(value));
    *field = value;
  }
  // Past these the scene would not fit in memory (or not be keyframed at all): refuse, don't crash.
  if (values.triangles > 5e7)
    throw InputError(where,
                     "triangles must be at most 5e7, got " + std::to_string(values.triangles));
  if (values.duration * values.keyrate > 1e5)
    throw InputError(where, "duration * keyrate must be at most 1e5 keys");
  return values;
}

Scene make_builtin_scene(const std::string& name, const std::map<std::string, double>& params) {
  const ProceduralParams values = builtin_scene_params(name, params);
  const std::string where = "scene '" + name + "'";
  const BuiltinScene* builtin = nullptr;
  for (const BuiltinScene& scene : builtin_scenes())
    if (scene.name == name) builtin = &scene;
  Scene scene = builtin->make(values);
  scene.name = name;
  scene.validate(where);
  return scene;
}

std::vector<double> procedural_key_times(double duration, double keyrate) {
  // The small tolerance keeps duration * keyrate = 48.000000001 from adding a 49th, tiny interval.
  const size_t intervals = std::max<size_t>(1, size_t(std::ceil(duration * keyrate - 1e-9)));
  std::vector<double> times(intervals + 1);
  for (size_t k = 0; k <= intervals; ++k) times[k] = duration * double(k) / double(intervals);
  return times;
}

}  // namespace kinray
