#pragma once
// The shape of a bounding volume hierarchy over triangles, built once by a static builder and
// kept while the kinetic trees move their boxes (Zachmann and Weller, VRCIA 2006: any builder of
// logarithmic height will do). One triangle per leaf; nodes in pre-order, so every child has a
// larger index than its parent and a reverse sweep visits children before parents.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace kinray {

inline constexpr uint32_t kNoNode = ~0u;

struct BvhNode {
  uint32_t left = kNoNode, right = kNoNode;  ///< children; kNoNode for a leaf
  uint32_t parent = kNoNode;
  uint32_t triangle = kNoNode;  ///< the leaf's triangle (global id)
  uint8_t axis = 0;             ///< the builder's split axis of an inner node
  [[nodiscard]] bool leaf() const { return left == kNoNode; }
};

/// An axis-aligned box.
struct Aabb {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  void extend(const Eigen::Vector3d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void extend(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  [[nodiscard]] double half_area() const {
    const Eigen::Vector3d d = (hi - lo).cwiseMax(0.0);
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  }
};

struct BvhTopology {
  std::vector<BvhNode> nodes;  ///< nodes[0] is the root (empty when there are no triangles)
  [[nodiscard]] uint32_t height() const;
};

/// Binned SAH (16 bins per axis on the centroids, Wald 2007) over the triangles' boxes, down to
/// one triangle per leaf; ties and degenerate centroid spreads split by median, so the height is
/// logarithmic in practice and bounded by the triangle count.
[[nodiscard]] BvhTopology build_binned_sah(std::span<const Aabb> triangle_boxes);

/// The tree collapsed to four children per node, for traversals that test four boxes at once:
/// wide node 0 holds the root's children, and each wide node up to four binary nodes, found by
/// opening the inner child with the most leaves below it first (which keeps the wide tree
/// balanced). Wide nodes are numbered in the order a depth-first walk creates them.
struct FourWideTopology {
  std::vector<uint32_t> binary;  ///< per wide node: the binary node it opens
  std::vector<std::array<uint32_t, 4>>
      children;                               ///< per wide node: slot k's binary node or kNoNode
  std::vector<std::array<uint32_t, 4>> wide;  ///< per wide node: an inner slot's wide node
};
/// The collapse of a tree whose root is an inner node (two triangles or more).
[[nodiscard]] FourWideTopology collapse_four_wide(const BvhTopology& topology);

}  // namespace kinray
