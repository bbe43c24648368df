#pragma once
// Diffuse (base colour) textures of imported models, read with OpenCV imgcodecs (and TGA, which it
// lacks, with model_tga.h) into linear-RGB kinray::Textures: files beside the model, or textures
// embedded in it ("*0", glb buffers, MDL skins). A texture that is missing or cannot be decoded is
// a documented repair: a warning (util/warning.h), and the material keeps its base colour alone.
#include <filesystem>
#include <optional>
#include <string>

#include "scenes/scene.h"

struct aiScene;

namespace kinray {

/// Reads the texture a material names with `reference`: an embedded texture ("*N", or the name
/// of one), else a file relative to `model_directory`; when that file does not exist, the file
/// name alone (after turning backslashes into slashes) is looked up beside the model, since many
/// exporters write absolute paths of the author's machine. Returns nothing, with a warning
/// naming `where`, when no readable image is found.
[[nodiscard]] std::optional<Texture> read_texture(const aiScene& scene,
                                                  const std::string& reference,
                                                  const std::filesystem::path& model_directory,
                                                  const std::string& where);

}  // namespace kinray
