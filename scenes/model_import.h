#pragma once
// Animated models through assimp (glTF 2 / GLB, FBX, COLLADA, X, MD5, BVH, OBJ, ...): node
// animation, skinning and morph targets are evaluated at key times and become piecewise-linear
// flightplans of the scene model, so every backend renders the same motion.
#include <string>

#include "scenes/scene.h"

namespace kinray {

struct ModelOptions {
  std::string animation;   ///< name or index; empty = the first animation
  double keyrate = 0;      ///< > 0: resample at this many keys per second; 0: union of the key times
  bool load_camera = true; ///< use the model's own camera if it has one, else frame automatically
};

/// True when `path` has an extension assimp can import.
[[nodiscard]] bool is_model_file(const std::string& path);

/// Loads `path` as a scene of its own (objects, materials, textures, camera, shot = the animation).
/// Throws InputError naming the file and the problem.
[[nodiscard]] Scene load_model(const std::string& path, const ModelOptions& options = {});

}  // namespace kinray
