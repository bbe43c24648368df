#pragma once
// What traces the kinetic backend's shadow rays, chosen by `--shadow-tree`
// (BackendConfig::shadow_tree): one function, so that the choice is made in one place.
#include <memory>
#include <string>

#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"

namespace kinray {

/// The shadow tracer of kind `kind` over `scene` (which must outlive it), auditing its kinetic
/// structure when `audit` is set.
[[nodiscard]] std::unique_ptr<ShadowTracer> make_kinetic_shadow_tracer(
    const CameraSpaceScene& scene, ShadowTree kind, bool audit);

}  // namespace kinray
