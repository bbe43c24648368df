#pragma once
// Shadow rays through the kinetic trees (docs/design.md, "Kinetic AABB tree and kinetic
// BoxTree"): the kinetic AABB tree, the kinetic BoxTree, or the same AABB tree updated bottom-up
// at every frame (`--shadow-tree aabb|boxtree|refit`). The tree is built at the first frame time
// and then only advanced: the kinetic trees process their events up to each frame time, the
// bottom-up tree recomputes its boxes.
#include <memory>

#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"

namespace kinray {

/// A shadow tracer over the camera-space triangles of `scene` (which must outlive it) for kind
/// aabb, boxtree or refit; `audit` audits a kinetic tree after every advance (tests). Throws
/// std::invalid_argument for ShadowTree::brute, which is not a tree.
[[nodiscard]] std::unique_ptr<ShadowTracer> make_tree_shadow_tracer(const CameraSpaceScene& scene,
                                                                    ShadowTree kind, bool audit);

}  // namespace kinray
