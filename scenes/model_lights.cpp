#include "scenes/model_lights.h"

#include <assimp/light.h>

#include "scenes/model_assimp.h"

namespace kinray {

std::vector<Light> model_lights(const aiScene& scene, const NodeGraph& graph, double first_tick,
                                const std::string& where) {
  std::vector<Light> lights;
  std::vector<Mat4> globals;
  if (scene.mNumLights > 0) graph.global_transforms(first_tick, globals);
  for (unsigned l = 0; l < scene.mNumLights && scene.mLights != nullptr; ++l) {
    const aiLight* source = scene.mLights[l];
    if (source == nullptr) continue;
    const std::string light_where = where + ": light '" + source->mName.C_Str() + "'";
    Light light;
    switch (source->mType) {
      case aiLightSource_POINT:
        break;
      case aiLightSource_SPOT:
        warn_repair(light_where, "is a spot light; kinray lights it as a point light (no cone)");
        break;
      case aiLightSource_DIRECTIONAL:
        light.kind = Light::Kind::directional;
        break;
      default:
        warn_repair(light_where, "is an ambient, area or undefined light, which kinray skips");
        continue;
    }
    const int node = graph.find(source->mName.C_Str());
    if (node < 0) {
      warn_repair(light_where, "has no node to place it; skipped");
      continue;
    }
    const Mat4& g = globals[size_t(node)];
    const Vec3 position = transform_point(g, to_eigen(source->mPosition));
    const Vec3 direction = g.topLeftCorner<3, 3>() * to_eigen(source->mDirection);
    const aiColor3D& c = source->mColorDiffuse;
    light.color = Color(c.r, c.g, c.b);
    const bool directional = light.kind == Light::Kind::directional;
    if (!position.allFinite() || !direction.allFinite() || !light.color.allFinite() ||
        (light.color.array() < 0).any() || !(light.color.maxCoeff() > 0) ||
        (directional && !(direction.norm() > 0))) {
      warn_repair(light_where,
                  "has a non-finite or degenerate position, direction or colour; skipped");
      continue;
    }
    light.position = position;
    if (directional) light.direction = direction.normalized();
    lights.push_back(light);
  }
  return lights;
}

}  // namespace kinray
