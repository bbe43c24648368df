#pragma once
// Where a mesh is on its flightplans, exactly as the kinetic grid reads it (GridScene::segment_at,
// vertex_motion), without the grid's scene index: the same segments and the same vertex motions,
// so that the two structures' certificates agree bit for bit.
#include <algorithm>
#include <cstdint>
#include <limits>

#include "kinetic/grid/grid_scene.h"
#include "kinetic/motion/flightplan_mesh.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {

/// The segment of `mesh` active just after t (a key time starts the new segment); a static mesh
/// stands still at its last key for ever.
[[nodiscard]] inline MeshSegment mesh_segment_at(const FlightplanMesh& mesh, double t) {
  const auto keys = mesh.key_times;
  const uint32_t n = uint32_t(keys.size());
  const uint32_t index =
      mesh.is_static ? n : uint32_t(std::upper_bound(keys.begin(), keys.end(), t) - keys.begin());
  MeshSegment seg;
  seg.index = index;
  seg.origin = keys[index == 0 ? 0 : index - 1];
  seg.end = index < n ? keys[index] : std::numeric_limits<double>::infinity();
  return seg;
}

/// Vertex `local` of `mesh` on `seg`, in the segment's local time.
[[nodiscard]] inline PointMotion mesh_vertex_motion(const FlightplanMesh& mesh, uint32_t local,
                                                    const MeshSegment& seg) {
  const uint32_t n = uint32_t(mesh.key_times.size());
  PointMotion p;
  if (seg.index == 0) {
    p.a = mesh.key_position(0, local);
  } else if (seg.index >= n) {
    p.a = mesh.key_position(n - 1, local);
  } else {
    const size_t k = seg.index;
    p.a = mesh.key_position(k - 1, local);
    p.b = (mesh.key_position(k, local) - p.a) / (mesh.key_times[k] - mesh.key_times[k - 1]);
  }
  return p;
}

}  // namespace kinray
