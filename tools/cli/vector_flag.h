#pragma once
// Three numbers X,Y,Z in a flag's value (--light, --eye, --target).
#include <optional>
#include <string>

#include "scenes/scene.h"

namespace kinray {

/// "X,Y,Z": three finite numbers separated by commas, nothing else (no spaces); nullopt otherwise.
[[nodiscard]] std::optional<Vec3> parse_vector3(const std::string& text);

}  // namespace kinray
