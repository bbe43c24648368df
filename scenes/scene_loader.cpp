#include "scenes/scene_loader.h"

#include <cctype>
#include <charconv>
#include <filesystem>
#include <map>
#include <sstream>

#include "scenes/aff_scene.h"
#include "scenes/mesh_sequence.h"
#include "scenes/procedural.h"
#include "scenes/scene_file.h"
#include "util/input_error.h"

namespace kinray {

namespace {

bool ends_with_json(const std::string& path) {
  if (path.size() < 5) return false;
  std::string extension = path.substr(path.size() - 5);
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension == ".json";
}

/// "triangles=2000,duration=1.5" -> {{"triangles", 2000}, {"duration", 1.5}}.
std::map<std::string, double> parse_parameters(const std::string& spec, const std::string& text) {
  std::map<std::string, double> params;
  std::istringstream items(text);
  std::string item;
  while (std::getline(items, item, ',')) {
    const size_t equals = item.find('=');
    if (equals == std::string::npos || equals == 0)
      throw InputError("scene '" + spec + "'", "expected key=value, got '" + item + "'");
    const std::string key = item.substr(0, equals), value = item.substr(equals + 1);
    double number = 0;
    const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
    if (error != std::errc() || end != value.data() + value.size() || value.empty())
      throw InputError("scene '" + spec + "'",
                       "parameter " + key + " needs a number, got '" + value + "'");
    if (!params.emplace(key, number).second)
      throw InputError("scene '" + spec + "'", "parameter " + key + " is given twice");
  }
  return params;
}

}  // namespace

std::optional<ProceduralParams> builtin_scene_params(const std::string& spec) {
  const size_t colon = spec.find(':');
  const std::string name = spec.substr(0, colon);
  if (!is_builtin_scene(name)) return std::nullopt;
  return builtin_scene_params(name, colon == std::string::npos
                                        ? std::map<std::string, double>{}
                                        : parse_parameters(spec, spec.substr(colon + 1)));
}

Scene load_scene(const std::string& spec, const ModelOptions& model_options,
                 ModelCatalog* catalog) {
  if (spec.empty())
    throw InputError("scene ''", "empty scene name; " + describe_scene_spec_syntax());
  const std::string name = spec.substr(0, spec.find(':'));
  if (is_builtin_scene(name)) {
    const size_t colon = spec.find(':');
    return make_builtin_scene(name, colon == std::string::npos
                                        ? std::map<std::string, double>{}
                                        : parse_parameters(spec, spec.substr(colon + 1)));
  }
  std::error_code error;
  if (is_mesh_sequence(spec)) return load_mesh_sequence(spec, model_options);
  if (ends_with_json(spec)) return load_scene_file(spec);
  if (std::filesystem::is_regular_file(spec, error)) {
    if (is_aff_file(spec)) return load_aff(spec, model_options.keyrate);
    if (is_model_file(spec)) {
      Scene scene = load_model(spec, model_options, catalog);
      scene.validate(spec);
      return scene;
    }
    throw InputError(spec, "neither a scene file (.json) nor a model format assimp can import");
  }
  if (std::filesystem::exists(spec, error)) throw InputError(spec, "not a regular file");
  const bool looks_like_path =
      spec.find('/') != std::string::npos || spec.find('.') != std::string::npos;
  if (looks_like_path) throw InputError(spec, "no such file");
  std::string names;
  for (const std::string& n : builtin_scene_names()) names += (names.empty() ? "" : ", ") + n;
  throw InputError("scene '" + spec + "'",
                   "neither a built-in scene (" + names + ") nor an existing file");
}

std::string describe_scene_spec_syntax() {
  std::ostringstream text;
  text << "A scene is a built-in name with optional parameters "
          "(NAME[:triangles=N,duration=S,keyrate=K]),\n"
          "a JSON scene file (*.json, see docs/scene_format.md), a BART scene (*.aff, docs/bart.md)\n"
          "a model file assimp can import (glTF, FBX, COLLADA, OBJ, ...), or a mesh sequence: a folder\n"
          "of .ply or .obj files or a quoted glob 'sim/frame_*.ply' (docs/mesh_sequences.md). Built-in scenes (defaults in brackets):\n";
  for (const BuiltinScene& scene : builtin_scenes()) {
    text << "  " << scene.name << " [triangles=" << scene.defaults.triangles
         << ", duration=" << scene.defaults.duration << ", keyrate=" << scene.defaults.keyrate;
    if (scene.defaults.gap) text << ", gap=" << *scene.defaults.gap;
    text << "]: " << scene.description << "\n";
  }
  text << "Example: cloth:triangles=2000,duration=1.5";
  return text.str();
}

}  // namespace kinray
