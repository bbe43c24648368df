#pragma once
// Where a mesh is on its flightplans: its key segment at a time and its vertices' motions on a
// segment. The kinetic grid (GridScene) and the per-square sets (kinetic/squares/) both read
// them here, so that the two structures' certificates agree bit for bit.
#include <algorithm>
#include <cstdint>
#include <limits>

#include "kinetic/motion/flightplan_mesh.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {

/// A mesh's key segment: `index` is the number of keys <= t: 0 stands still at key 0 until K_0,
/// 1..n-1 moves from key index-1 to key index over [K_{index-1}, K_index), n stands still at the
/// last key. Polynomials use the local time s = t - origin.
struct MeshSegment {
  uint32_t index = 0;
  double origin = 0;
  double end = std::numeric_limits<double>::infinity();  ///< the next flightplan update
};

/// Segment `index` of `mesh`.
[[nodiscard]] inline MeshSegment mesh_segment(const FlightplanMesh& mesh, uint32_t index) {
  const auto keys = mesh.key_times;
  const uint32_t n = uint32_t(keys.size());
  MeshSegment seg;
  seg.index = index;
  seg.origin = keys[index == 0 ? 0 : index - 1];
  seg.end = index < n ? keys[index] : std::numeric_limits<double>::infinity();
  return seg;
}

/// The segment of `mesh` active just after t (a key time starts the new segment); a static mesh
/// stands still at its last key for ever.
[[nodiscard]] inline MeshSegment mesh_segment_at(const FlightplanMesh& mesh, double t) {
  const auto keys = mesh.key_times;
  const uint32_t n = uint32_t(keys.size());
  const uint32_t index =
      mesh.is_static ? n : uint32_t(std::upper_bound(keys.begin(), keys.end(), t) - keys.begin());
  return mesh_segment(mesh, index);
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
