#pragma once
// `kinray render --contacts`: which triangles each frame tints. The contacts come from
// find_scene_contacts (scene_contacts.h) over the rendered frames' windows, self-contacts
// included; a triangle is in contact at frame i when one of its vertices, edges or its face takes
// part in a contact whose time lies in frame i's window (contact_window_bounds, contact_tint.h).
#include <cstdint>
#include <vector>

#include "kinetic/collision/mesh_contacts.h"
#include "renderer/job/frame_slice.h"
#include "scenes/scene.h"

namespace kinray {

/// For each frame of `frame_times` (frames outside `slice` stay empty), the sorted keys of the
/// triangles in contact during its window: for a vertex in contact every triangle around it, for
/// an edge every triangle holding both its ends, for a face the face. Runs the contact search over
/// the slice's windows.
[[nodiscard]] std::vector<std::vector<uint64_t>> contact_tint_frames(
    const Scene& scene, const std::vector<double>& frame_times, const FrameSlice& slice);

}  // namespace kinray
