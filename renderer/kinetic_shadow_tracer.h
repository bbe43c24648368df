#pragma once
// What traces the kinetic backend's shadow rays, chosen by `--shadow-tree`
// (BackendConfig::shadow_tree): one function, so that the choice is made in one place.
#include <memory>
#include <string>

#include "renderer/shadow_tracer.h"
#include "scenes/camera_space.h"

namespace kinray {

/// "aabb", "boxtree", "refit" or "brute" as a ShadowTree; throws InputError naming --shadow-tree.
[[nodiscard]] ShadowTree parse_shadow_tree(const std::string& name);
/// The name parse_shadow_tree reads.
[[nodiscard]] const char* shadow_tree_name(ShadowTree kind);

/// The shadow tracer of kind `kind` over `scene` (which must outlive it), auditing its kinetic
/// structure when `audit` is set. Throws InputError naming --shadow-tree for a kind this build
/// cannot make.
[[nodiscard]] std::unique_ptr<ShadowTracer> make_kinetic_shadow_tracer(
    const CameraSpaceScene& scene, ShadowTree kind, bool audit);

}  // namespace kinray
