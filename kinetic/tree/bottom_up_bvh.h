#pragma once
// The baseline of the kinetic trees (Zachmann and Weller's "bottom-up update"): the same tree
// (same builder, same input, so the same shape), with every box recomputed at each frame from the
// vertex positions at that time, leaves first. It shares the queries of tree_query.h, so a
// comparison with the kinetic trees isolates the update.
#include <cstdint>
#include <vector>

#include "kinetic/tree/bvh_topology.h"
#include "kinetic/tree/tree_meshes.h"
#include "kinetic/tree/tree_query.h"

namespace kinray {

class BottomUpBvh {
 public:
  /// Builds the tree at time t (the kinetic trees' builder on the same boxes).
  BottomUpBvh(std::vector<FlightplanMesh> meshes, double t);

  /// Recomputes every box at t: the present meshes' vertex positions, the leaves, then parents.
  void update(double t);
  [[nodiscard]] double time() const { return m_time; }
  /// Boxes recomputed so far (one per node per update): the "BV updates" of the comparison.
  [[nodiscard]] uint64_t box_updates() const { return m_box_updates; }
  [[nodiscard]] uint64_t updates() const { return m_updates; }

  [[nodiscard]] const TreeMeshes& meshes() const { return m_meshes; }
  [[nodiscard]] const BvhTopology& topology() const { return m_topology; }
  [[nodiscard]] const Aabb& box(uint32_t node) const { return m_boxes[node]; }
  /// Vertex v at the last update (TreeMeshes::position's arithmetic).
  [[nodiscard]] const Eigen::Vector3d& position(uint32_t v) const { return m_positions[v]; }
  [[nodiscard]] size_t memory_bytes() const;

  /// tree_query.h's box source: the stored boxes, padded like the kinetic trees' boxes.
  [[nodiscard]] Aabb root_box(const TreeFrame& frame) const { return padded(0, frame); }
  void child_boxes(const BvhNode& n, const Aabb&, const TreeFrame& frame, Aabb& left,
                   Aabb& right) const {
    left = padded(n.left, frame);
    right = padded(n.right, frame);
  }

 private:
  [[nodiscard]] Aabb padded(uint32_t node, const TreeFrame& frame) const {
    if (m_boxes.empty()) return Aabb{};
    Aabb b = m_boxes[node];
    b.lo.array() -= frame.pad;
    b.hi.array() += frame.pad;
    return b;
  }

  TreeMeshes m_meshes;
  BvhTopology m_topology;
  std::vector<Aabb> m_boxes;
  std::vector<Eigen::Vector3d> m_positions;  ///< per global vertex, at the last update
  std::vector<FlightplanMesh::KeyBlend> m_blends;
  double m_time = 0;
  uint64_t m_box_updates = 0, m_updates = 0;
};

}  // namespace kinray
