#include "renderer/shadows/kinetic_shadow_tracer.h"

#include "renderer/shadows/brute_force_shadow_tracer.h"
#include "renderer/shadows/tree_shadow_tracer.h"

namespace kinray {

std::unique_ptr<ShadowTracer> make_kinetic_shadow_tracer(const CameraSpaceScene& scene,
                                                         ShadowTree kind, bool audit) {
  // Brute force has nothing to audit; the kinetic trees audit after every advance.
  if (kind == ShadowTree::brute) return std::make_unique<BruteForceShadowTracer>(scene);
  return make_tree_shadow_tracer(scene, kind, audit);
}

}  // namespace kinray
