#pragma once
// Built-in procedural scenes. Each is deterministic and keyframed: vertex positions are sampled
// at key times (`keyrate` keys per second over [0, duration]) and become the piecewise-linear
// flightplans of Object::key_positions, exactly as an imported animation would.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace kinray {

/// The parameters every built-in scene takes.
struct ProceduralParams {
  double triangles = 40000;  ///< approximate triangle count (each scene has a small floor)
  double duration = 2;       ///< seconds: the shot is [0, duration]
  double keyrate = 24;       ///< keys per second
  /// The near-miss scenes' smallest distance between the surfaces (<= 0: they may touch); the
  /// other scenes take no gap and leave it empty.
  std::optional<double> gap;
};

/// A built-in scene: its name, one line on what it shows, and its default parameters.
struct BuiltinScene {
  std::string name;
  std::string description;
  ProceduralParams defaults;
  Scene (*make)(const ProceduralParams&) = nullptr;
};

/// Every built-in scene; the first, wavy-sphere, is the default scene and the benchmark scene.
[[nodiscard]] const std::vector<BuiltinScene>& builtin_scenes();
[[nodiscard]] std::vector<std::string> builtin_scene_names();
[[nodiscard]] bool is_builtin_scene(const std::string& name);

/// The parameters of the built-in `name` with `params` over its defaults, checked as
/// make_builtin_scene checks them (it throws the same InputErrors) without building anything.
[[nodiscard]] ProceduralParams builtin_scene_params(const std::string& name,
                                                    const std::map<std::string, double>& params);

/// Builds the built-in `name` with `params` (keys "triangles", "duration", "keyrate", and "gap" for
/// the scenes that take one; missing ones take the scene's defaults). Throws InputError for an
/// unknown name or parameter, listing the valid ones, and for non-finite values or non-positive
/// ones (the gap may be zero or negative).
[[nodiscard]] Scene make_builtin_scene(const std::string& name,
                                       const std::map<std::string, double>& params = {});

/// Key times 0 = t_0 < ... < t_n = duration, evenly spaced, n = ceil(duration * keyrate) >= 1.
[[nodiscard]] std::vector<double> procedural_key_times(double duration, double keyrate);

// The scenes themselves (procedural_<name>.cpp); parameters are taken as given (checked by
// make_builtin_scene).

/// A sphere that spins slowly while travelling waves run over its surface; fixed camera, fov 45.
[[nodiscard]] Scene make_wavy_sphere(const ProceduralParams& params);
/// A hanging cloth whose lower part curls up in front of, then behind, its upper part.
[[nodiscard]] Scene make_cloth(const ProceduralParams& params);
/// Spheres and boxes orbiting a central sphere, passing in front of each other and through it.
[[nodiscard]] Scene make_orbit(const ProceduralParams& params);
/// A camera flight (position, orientation and fov keyed) between pillars and under lintels.
[[nodiscard]] Scene make_flythrough(const ProceduralParams& params);
/// A static ground and wall, a bouncing ball, and a spinning box that appears and disappears.
[[nodiscard]] Scene make_static_moving(const ProceduralParams& params);
/// A rippled sheet whose right half folds through 200 degrees onto and through its left half.
[[nodiscard]] Scene make_cloth_fold(const ProceduralParams& params);
/// Two wobbling spheres travelling towards each other and through each other.
[[nodiscard]] Scene make_crossing(const ProceduralParams& params);
/// Two wobbling spheres gliding past each other, their surfaces at least `gap` apart.
[[nodiscard]] Scene make_glide(const ProceduralParams& params);
/// A flat cloth sliding over a still sphere that lifts it, its vertices `gap` above it.
[[nodiscard]] Scene make_cloth_slide(const ProceduralParams& params);
/// An arm of two links and a hand swinging like a double pendulum, the hand `gap` above a floor.
[[nodiscard]] Scene make_swing(const ProceduralParams& params);

}  // namespace kinray
