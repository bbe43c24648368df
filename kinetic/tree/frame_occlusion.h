#pragma once
// Occlusion (any hit) of many rays through one frame's boxes at once, their traversals
// interleaved: a lane steps one ray by one wide node, then the next lane steps its ray, so that
// the nodes a step prefetches arrive while the other lanes work. A shadow ray's traversal visits
// some 17 wide nodes of a 100,000-triangle tree and waits on memory at most of them (the nodes
// of a frame do not fit in the 1 MB second-level caches of some of these machines, and
// neighbouring shadow rays share only the top of their paths); one ray at a time leaves nothing
// to do while a node loads. Whether a ray meets some triangle does not depend on the order its
// nodes are visited in, so the answers are any_hit's of tree_query.h on the same tree.
#include <cstdint>
#include <span>

#include "kinetic/tree/frame_boxes.h"

namespace kinray {

/// blocked[i] = 1 when rays[i] meets some present triangle at the frame's time (within
/// (s_min, s_max), never its `skip` triangle), else 0; the spans have the same length.
void frame_occluded(const FrameBoxes& boxes, std::span<const TreeRay> rays,
                    std::span<uint8_t> blocked);

}  // namespace kinray
