#include "renderer/kinetic_shadow_tracer.h"

#include "renderer/brute_force_shadow_tracer.h"
#include "renderer/tree_shadow_tracer.h"
#include "scenes/error.h"

namespace kinray {

ShadowTree parse_shadow_tree(const std::string& name) {
  if (name == "aabb") return ShadowTree::aabb;
  if (name == "boxtree") return ShadowTree::boxtree;
  if (name == "refit") return ShadowTree::refit;
  if (name == "brute") return ShadowTree::brute;
  throw InputError("--shadow-tree",
                   "must be one of aabb, boxtree, refit, brute, got '" + name + "'");
}

const char* shadow_tree_name(ShadowTree kind) {
  switch (kind) {
    case ShadowTree::aabb:
      return "aabb";
    case ShadowTree::boxtree:
      return "boxtree";
    case ShadowTree::refit:
      return "refit";
    case ShadowTree::brute:
      return "brute";
  }
  return "?";
}

std::unique_ptr<ShadowTracer> make_kinetic_shadow_tracer(const CameraSpaceScene& scene,
                                                         ShadowTree kind, bool audit) {
  // Brute force has nothing to audit; the kinetic trees audit after every advance.
  if (kind == ShadowTree::brute) return std::make_unique<BruteForceShadowTracer>(scene);
  return make_tree_shadow_tracer(scene, kind, audit);
}

}  // namespace kinray
