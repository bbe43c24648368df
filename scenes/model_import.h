#pragma once
// Animated models through assimp (glTF 2 / GLB, FBX, COLLADA, X, MD5, BVH, OBJ, ...): node
// animation, skinning and morph targets are evaluated at key times and become piecewise-linear
// flightplans of the scene model, so every backend renders the same motion.
#include <string>

#include "scenes/model_catalog.h"
#include "scenes/scene.h"

struct aiScene;

namespace kinray {

/// Which camera a model is shown with (`--camera`).
enum class ModelCamera {
  own_if_usable,  ///< the default: the model's own camera when it sees the model, else automatic
  own,            ///< --camera model: the model's own camera; InputError naming --camera if none
  automatic,      ///< --camera auto: automatic framing (scenes/automatic_camera.h)
};

struct ModelOptions {
  std::string animation;  ///< name or index; empty = the first animation
  double keyrate = 0;     ///< > 0: resample at this many keys per second; 0: union of the key times
  ModelCamera camera = ModelCamera::own_if_usable;  ///< which camera the scene gets
  bool isolate_import = true;   ///< read the file in a child process first (see model_guard.h)
  double import_timeout = 300;  ///< seconds that child may take before the file counts as hostile
};

/// True when `path` has an extension assimp can import.
[[nodiscard]] bool is_model_file(const std::string& path);

/// Loads `path` as a scene of its own (objects, materials, textures, camera, shot = the animation);
/// fills `catalog`, when given, with the model's animations and cameras.
/// Throws InputError naming the file and the problem.
[[nodiscard]] Scene load_model(const std::string& path, const ModelOptions& options = {},
                               ModelCatalog* catalog = nullptr);

/// The assimp post-processing flags load_model reads files with: triangulate, join identical
/// vertices, validate the data structure; never pre-transform vertices (that loses animation).
[[nodiscard]] unsigned model_import_flags();

/// Turns an imported (or hand-built) aiScene into a scene; `source` names it in errors and
/// warnings, and textures are looked up beside it. Does not call Scene::validate. Throws
/// InputError.
[[nodiscard]] Scene convert_model(const aiScene& model, const std::string& source,
                                  const ModelOptions& options = {});

}  // namespace kinray
