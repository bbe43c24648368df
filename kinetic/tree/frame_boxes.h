#pragma once
// The boxes of one frame, evaluated once for every query of that frame, in a compact layout: one
// 64-byte node per inner node of the tree holding both children's float boxes (rounded outward
// from the padded double boxes, so each contains the box the lazy traversal of tree_query.h
// evaluates and no hit is lost) and the children's links; the triangles are placed exactly as
// TreeMeshes::position places them (the exact double triangle test, hence the same hits). A
// traversal step reads one cache line and tests both children, instead of evaluating twelve
// realizers' motions. Filled from the kinetic AABB tree, the kinetic BoxTree (a child is its
// parent's box cut by the sides it tracks) or the bottom-up tree's stored boxes.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "kinetic/tree/tree_query.h"

namespace kinray {

class FrameBoxes {
 public:
  /// An inner node: child c's box is lo = box[c][0..2], hi = box[c][3..5] (lo > hi: absent), its
  /// link an inner node's index here or kLeaf | triangle.
  struct alignas(64) Node {
    std::array<std::array<float, 6>, 2> box;
    std::array<uint32_t, 2> link;
    uint32_t padding[2];
  };
  static constexpr uint32_t kLeaf = 1u << 31;

  /// The kinetic tree's boxes at frame.t (its realizers' coordinates, padded by frame.pad).
  void fill(const KineticBvh& tree, const TreeFrame& frame);
  /// The bottom-up tree's stored boxes (its last update), padded by frame.pad.
  void fill(const BottomUpBvh& tree, const TreeFrame& frame);

  /// The root's box and link (kNoNode when the tree is empty).
  [[nodiscard]] const std::array<float, 6>& root_box() const { return m_root_box; }
  [[nodiscard]] uint32_t root_link() const { return m_root_link; }
  [[nodiscard]] const Node& node(uint32_t k) const { return m_nodes[k]; }
  /// Vertex v at the frame's time, as TreeMeshes::position places it (evaluated when tested: a
  /// frame's shadow rays test far fewer vertices than the meshes have).
  [[nodiscard]] Eigen::Vector3d position(uint32_t v) const {
    return m_meshes->position(v, m_frame->blends);
  }
  [[nodiscard]] const TreeMeshes& meshes() const { return *m_meshes; }
  [[nodiscard]] size_t memory_bytes() const {
    return m_nodes.capacity() * sizeof(Node) + m_slot.capacity() * sizeof(uint32_t) +
           m_coordinates.capacity() * sizeof(double);
  }

 private:
  /// The links (once per topology).
  void prepare(const BvhTopology& topology, const TreeMeshes& meshes, const TreeFrame& frame);
  /// Where node i's box goes: its parent's compact node * 2 + side (the root: kNoNode).
  [[nodiscard]] std::array<float, 6>& slot(uint32_t i) {
    return m_slot[i] == kNoNode ? m_root_box : m_nodes[m_slot[i] >> 1].box[m_slot[i] & 1];
  }

  const TreeMeshes* m_meshes = nullptr;
  const BvhTopology* m_topology = nullptr;
  std::vector<Node> m_nodes;
  std::vector<uint32_t> m_slot;
  std::array<float, 6> m_root_box{};
  uint32_t m_root_link = kNoNode;
  const TreeFrame* m_frame = nullptr;  ///< the frame filled (it must outlive the queries)
  std::vector<double> m_coordinates;  ///< per vertex and axis: a + b (t - o), the realizers' values
};

/// Closest hit (any = false) or any hit through the frame's boxes; the same answers as
/// closest_hit / any_hit of tree_query.h on the tree they were filled from.
[[nodiscard]] std::optional<TreeHit> frame_traverse(const FrameBoxes& boxes, const TreeRay& ray,
                                                    bool any);

}  // namespace kinray
