#pragma once
// One way to name a scene on the command line: a built-in with optional parameters
// ("wavy-sphere", "cloth:triangles=2000,duration=1.5"), a JSON scene file, or a model file.
#include <optional>
#include <string>

#include "scenes/model_import.h"
#include "scenes/procedural.h"
#include "scenes/scene.h"

namespace kinray {

/// Loads the scene named by `spec`: a built-in name (optionally followed by
/// ":key=value,key=value"), a path ending in .json (a scene file), or a path to a file assimp can
/// import (loaded with `model_options`; `catalog`, when given, gets the model's animations and
/// cameras). Throws InputError naming the spec or file and the problem.
[[nodiscard]] Scene load_scene(const std::string& spec, const ModelOptions& model_options = {},
                               ModelCatalog* catalog = nullptr);

/// The checked parameters of a built-in scene spec, without building it; nullopt when `spec` does
/// not name a built-in. Throws InputError for bad parameters, as load_scene does.
[[nodiscard]] std::optional<ProceduralParams> builtin_scene_params(const std::string& spec);

/// A few lines describing the spec syntax and the built-in scenes with their defaults, for --help.
[[nodiscard]] std::string describe_scene_spec_syntax();

}  // namespace kinray
