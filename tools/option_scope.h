#pragma once
// Flags that only some backends or scenes read: given where nothing reads them they would be
// ignored without a word, so they are refused, naming the flag and what it applies to.
#include <span>
#include <string>

#include "renderer/job/render_job.h"

namespace kinray {

/// Throws InputError when `params` sets a flag that none of `backends` (the backends the command
/// runs: render's --backend, or diff's backend and reference) reads -- --packet or --embree-mode
/// without embree, --sort or --audit without kinetic -- or a model flag (--animation, --keyrate)
/// on a built-in scene or a .json scene file. Flags left at their defaults are not checked.
void check_options_apply(const RenderParams& params, std::span<const std::string> backends);

}  // namespace kinray
