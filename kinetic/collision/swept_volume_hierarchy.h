#pragma once
// The swept-volume baseline of continuous collision detection: per collision-check interval, a
// bounding volume hierarchy over the box each triangle sweeps on that interval, built once and
// refitted for every later interval, traversed, and the same primitive tests on the triangle
// pairs whose swept boxes overlap. Its work grows with the number of intervals asked for, which
// is what the kinetic separation list avoids.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "kinetic/collision/mesh_contacts.h"

namespace kinray {

class SweptVolumeHierarchy {
 public:
  /// Swept boxes of `mesh`'s triangles on its interval (the collision check's), grown by `pad`:
  /// builds the tree on the first call, refits it (same topology, new boxes) on later calls with
  /// the same triangles.
  void update(const MeshSweep& mesh, double pad = 0);

  /// Contacts of the triangles of `query` (another hierarchy, or this one for the non-adjacent
  /// pairs of a mesh with itself) against this one's, whose boxes overlap: the primitive tests
  /// run on the flightplan segment [time_begin, time_end] of `a` (query's mesh) and `b` (this
  /// one's), and keep the contacts whose time lies in [window_begin, window_end): the check
  /// interval's (-inf and +inf at the segment's ends), so that checks on sub-intervals find
  /// exactly the segment's contacts, each once.
  void contacts(const SweptVolumeHierarchy& query, const MeshSweep& a, const MeshSweep& b,
                double time_begin, double time_end, double window_begin, double window_end,
                std::vector<Contact>& out, ContactCounters& counters) const;

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    std::uint32_t first = 0, count = 0;  ///< leaf: range of m_order; inner: count == 0
    std::uint32_t left = 0, right = 0;   ///< children of an inner node (indices > this one)
  };
  std::uint32_t build(std::uint32_t first, std::uint32_t count);

  std::vector<Eigen::AlignedBox3d> m_boxes;  ///< per triangle
  std::vector<std::uint32_t> m_order;        ///< triangles in leaf order
  std::vector<Node> m_nodes;                 ///< m_nodes[0] is the root
};

/// The box swept by triangle t of `mesh` over its segment (linear motion stays in the box of
/// the start and end positions).
[[nodiscard]] Eigen::AlignedBox3d swept_box(const MeshSweep& mesh, std::uint32_t t);

}  // namespace kinray
