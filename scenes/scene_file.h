#pragma once
// JSON scene files (docs/scene_format.md): the shot, materials, an animated camera, and objects
// that are inline meshes, primitives (sphere, box, grid), imported models or built-in procedural
// scenes, each keyed in seconds. Every mistake in a file is reported as one InputError naming the
// file, the JSON pointer of the offending value (like /objects/2/keys/1/time) and the problem.
#include <string>

#include "scenes/scene.h"

namespace kinray {

/// Reads and validates the scene file at `path`; relative paths inside it (textures, models)
/// are resolved against the file's folder.
[[nodiscard]] Scene load_scene_file(const std::string& path);

/// Parses `text` as the contents of a scene file at `path` (which names the file in errors and
/// anchors its relative paths; the file itself is not read).
[[nodiscard]] Scene parse_scene_file(const std::string& text, const std::string& path);

/// Writes `scene` as a self-contained scene file: every object as an inline mesh with one vertex
/// array per key, camera keys as quaternions, textures by absolute path. Loading it gives back the
/// same scene (positions, times and colours bit for bit). Throws InputError when it cannot write.
void save_scene_file(const Scene& scene, const std::string& path);

}  // namespace kinray
