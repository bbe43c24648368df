#pragma once
// The lights of an imported model (assimp's aiLight), placed in world space by their nodes at the
// first key: kinray's lights do not move, so an animated light node stands where the shot starts.
#include <assimp/scene.h>

#include <span>
#include <string>
#include <vector>

#include "scenes/model_animation.h"
#include "scenes/scene.h"

namespace kinray {

/// Point and directional lights of `scene`; a spot light becomes a point light at its position
/// (kinray has no cone), ambient, area and undefined lights are skipped, each with a warning on
/// stderr; so are lights without a node and lights whose position, direction or colour are not
/// finite or whose colour is black. The colour is aiLight::mColorDiffuse.
[[nodiscard]] std::vector<Light> model_lights(const aiScene& scene, const NodeGraph& graph,
                                              double first_tick, const std::string& where);

}  // namespace kinray
