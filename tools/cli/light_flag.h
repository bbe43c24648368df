#pragma once
// `--light point:X,Y,Z[:R,G,B]` and `--light dir:X,Y,Z[:R,G,B]`: world-space lights given on the
// command line (repeatable; they replace the scene's own lights).
#include <string>

#include "scenes/scene.h"

namespace kinray {

/// Parses one --light value. A directional light's X,Y,Z is the direction it shines along (from
/// the light towards the scene), normalized here; the colour defaults to white (1,1,1) and may
/// exceed 1 (an intensity). Throws InputError naming --light for anything else.
[[nodiscard]] Light parse_light_flag(const std::string& text);

}  // namespace kinray
