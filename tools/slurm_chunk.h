#pragma once
// `--chunk slurm`: the chunk of a Slurm job array task, from the variables Slurm sets for it, so
// that one batch script serves every array size (docs/render_farm.md).
#include <functional>
#include <string>

#include "renderer/job/frame_slice.h"

namespace kinray {

/// Reads a variable of the environment (nullptr when unset): std::getenv, or a test's table.
using EnvironmentLookup = std::function<const char*(const char* name)>;

/// The chunk I/N of the task of a job array: N = SLURM_ARRAY_TASK_COUNT, and I the task's place
/// among the array's indices, 1 + (SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN) /
/// SLURM_ARRAY_TASK_STEP (step 1 when unset). Throws InputError naming --chunk outside a job array,
/// and for an array whose indices are not one evenly spaced range (--array=1,4,9), whose places
/// Slurm does not say.
[[nodiscard]] FrameChunk slurm_array_chunk(const EnvironmentLookup& lookup);

}  // namespace kinray
