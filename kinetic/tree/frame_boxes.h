#pragma once
// The boxes of one frame for every query of that frame, in a 4-wide layout: the binary tree is
// collapsed once (each wide node holds up to four binary nodes, opening the largest inner child
// first), and a wide node's four children's float boxes (rounded outward from the padded double
// boxes, so each contains the box the lazy traversal of tree_query.h evaluates) lie side by side
// for one SSE slab test of all four (wide_slab_test.h, conservative: no hit is lost). The
// triangles are placed exactly as TreeMeshes::position places them (the exact double triangle
// test, hence the same hits). The boxes come from the kinetic AABB tree, the kinetic BoxTree (a
// child is its parent's box cut by the sides it tracks) or the bottom-up tree's stored boxes.
//
// A wide node's boxes are evaluated when a query of the frame first reaches it: a frame's
// shadow rays meet a fraction of the nodes (they start on the surface and most leave it), and
// evaluating every node was most of a frame's shadow time at 128x128. Queries run on several
// threads: the first to reach a node fills it and publishes it with a release store of the
// frame's stamp; the others wait for that stamp.
#include <array>
#include <atomic>
#include <cstdint>
#include <optional>
#include <vector>

#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "kinetic/tree/ray_triangle_filter.h"
#include "kinetic/tree/tree_query.h"

namespace kinray {

class FrameBoxes {
 public:
  /// A wide node: child k's box is rows bound[0..2][k] (low x, y, z) and bound[3..5][k] (high);
  /// an empty or unused child has low +inf and high -inf. link[k] is a wide node's index,
  /// kLeaf | triangle, or kNoLink for an unused slot.
  struct alignas(64) Node {
    float bound[6][4];
    std::array<uint32_t, 4> link;
    uint32_t used = 0;    ///< bit k set when slot k holds a child
    uint32_t binary = 0;  ///< the binary node it stands for
    uint32_t stamp = 0;   ///< the frame whose boxes it holds (atomic_ref), or that frame + 1
    /// The kinetic AABB tree's children as of this frame: bit k set when slot k's node is active,
    /// and its six realizers. A copy, which the tree's realizer changes keep current (track()):
    /// evaluating the node reads it with the node's lines, which the traversal prefetches, not
    /// four node states elsewhere in the tree (a 64-byte line each, missed at 100,000 triangles).
    uint32_t present = 0;
    uint32_t realizer[4][6] = {};
  };
  static_assert(sizeof(Node) == 256);
  static constexpr uint32_t kLeaf = 1u << 31;
  static constexpr uint32_t kNoLink = ~0u;

  /// Keeps the copy of the kinetic AABB tree's realizers in the wide nodes current as the tree
  /// advances: its realizer observer logs each change, and the next fill() applies the log
  /// (this object must then stay in place while the tree lives). Without it, fill() copies every
  /// realizer at each frame.
  void track(KineticBvh& tree);
  /// The kinetic tree's boxes at frame.t (its realizers' coordinates, padded by frame.pad). The
  /// tree and the frame must stay unchanged while the frame's queries run.
  void fill(const KineticBvh& tree, const TreeFrame& frame);
  /// The bottom-up tree's stored boxes (its last update), padded by frame.pad.
  void fill(const BottomUpBvh& tree, const TreeFrame& frame);

  /// The root's box (low x, y, z, high x, y, z) and link (kNoLink when the tree is empty).
  [[nodiscard]] std::array<float, 6> root_box() const {
    std::array<float, 6> b;
    for (int r = 0; r < 6; ++r) b[size_t(r)] = m_root_bound[r][0];
    return b;
  }
  /// The root's box as column 0 of a wide node's rows (the other columns empty): what a query
  /// tests first, laid out once per frame.
  [[nodiscard]] const float (&root_bound() const)[6][4] { return m_root_bound; }
  [[nodiscard]] uint32_t root_link() const { return m_root_link; }
  /// Wide node k with its children's boxes of this frame (evaluated on first use; thread-safe).
  [[nodiscard]] const Node& node(uint32_t k) const {
    Node& n = m_nodes[k];  // mutable: evaluated on first use
    if (std::atomic_ref<uint32_t>(n.stamp).load(std::memory_order_acquire) != m_stamp) [[unlikely]]
      evaluate(k);
    return n;
  }
  /// Starts loading wide node k's lines (a query about to visit it; not evaluated here): its
  /// boxes and links, and for the kinetic AABB tree the realizer copy its evaluation reads.
  void prefetch(uint32_t k) const {
    const char* line = reinterpret_cast<const char*>(&m_nodes[k]);
    for (int l = 0; l < m_prefetch_lines; ++l) __builtin_prefetch(line + 64 * l);
  }
  /// The float box of binary node i when a wide node holds it (every node but the root and the
  /// inner nodes the collapse opened); nullopt otherwise.
  [[nodiscard]] std::optional<std::array<float, 6>> box_of(uint32_t i) const;
  /// Vertex v at the frame's time, as TreeMeshes::position places it (evaluated when tested: a
  /// frame's shadow rays test far fewer vertices than the meshes have).
  [[nodiscard]] Eigen::Vector3d position(uint32_t v) const {
    return m_meshes->position(v, m_frame->blends);
  }
  /// Vertex v at the frame's time to the nearest floats (x, y, z, unused): each coordinate within
  /// 2^-24 of itself and the frame's pad of position(v), which RayTriangleFilter allows for.
  [[nodiscard]] const float* point(uint32_t v) const { return m_vertex_point[v].c; }
  [[nodiscard]] const TreeMeshes& meshes() const { return *m_meshes; }
  [[nodiscard]] const TreeFrame& frame() const { return *m_frame; }
  /// Where the ray meets the triangle at the frame's time, when in (ray.s_min, s_max) and the
  /// triangle is not the one it skips: the exact double test, behind the filter's rejection from
  /// the float points (the ray's own filter, built with this frame's pad).
  [[nodiscard]] std::optional<double> triangle_hit(uint32_t triangle, const TreeRay& ray,
                                                   const RayTriangleFilter& filter,
                                                   double s_max) const {
    if (triangle == ray.skip) return std::nullopt;
    const auto& v = m_meshes->triangle(triangle);
    if (filter.misses(point(v[0]), point(v[1]), point(v[2]))) return std::nullopt;
    const std::optional<double> s =
        ray_triangle(ray.origin, ray.direction, position(v[0]), position(v[1]), position(v[2]));
    if (s && *s > ray.s_min && *s < s_max) return s;
    return std::nullopt;
  }
  [[nodiscard]] size_t memory_bytes() const {
    return m_nodes.capacity() * sizeof(Node) + m_slot.capacity() * sizeof(uint32_t) +
           m_children.capacity() * sizeof(m_children[0]) +
           m_changes.capacity() * sizeof(RealizerChange) +
           m_vertex_point.capacity() * sizeof(m_vertex_point[0]);
  }

 private:
  /// The wide nodes' copy of the kinetic AABB tree's presence and realizers (track()).
  void copy_realizers(const KineticBvh& tree);
  /// Applies the logged realizer changes to the copy.
  void apply_changes();
  /// The collapse (once per topology).
  void prepare(const BvhTopology& topology, const TreeMeshes& meshes, const TreeFrame& frame);
  /// Fills wide node k's boxes for this frame (its parent's first), or waits for the thread
  /// that does.
  void evaluate(uint32_t k) const;
  /// The kinetic AABB tree's part of evaluate: wide node k's children's own boxes, from their
  /// realizers' vertex boxes, in SSE.
  void aabb_children(Node& n, uint32_t k) const;
  /// Binary node i's box this frame, given its parent's (the BoxTree's cut; the AABB tree's and
  /// the bottom-up tree's own box).
  [[nodiscard]] std::array<float, 6> box(uint32_t i, const std::array<float, 6>& parent) const;

  const TreeMeshes* m_meshes = nullptr;
  const BvhTopology* m_topology = nullptr;
  const KineticBvh* m_kinetic = nullptr;  ///< the source of this frame's boxes, or
  const BottomUpBvh* m_bottom_up = nullptr;
  const KineticBvh* m_tracked = nullptr;  ///< the tree whose observer updates the copy
  const KineticBvh* m_copy_of = nullptr;  ///< the tree the wide nodes' realizers are copied from
  uint64_t m_copy_presence = 0;           ///< its presence_changes() at the copy
  int m_prefetch_lines = 2;  ///< of a wide node: 4 where evaluation reads the realizer copy
  /// The realizer changes since the last fill, in order (node, side, new realizer): logged by
  /// the observer, a sequential write while the tree works on the node, and applied in one pass
  /// by fill(), a query cost: written straight into the wide nodes, each change was a missed
  /// line inside the tree's events and keys (+3% on its update, wavy-sphere 100k at 128
  /// in-betweens; the log: none measurable).
  struct RealizerChange {
    uint32_t node, side, realizer;
  };
  std::vector<RealizerChange> m_changes;
  bool m_changes_dropped = false;  ///< the log outgrew a full copy's cost and was dropped
  mutable std::vector<Node> m_nodes;
  std::vector<uint32_t> m_slot;  ///< per binary node: wide node * 4 + slot, or kNoLink
  std::vector<std::array<uint32_t, 4>> m_children;  ///< per wide node: its slots' binary nodes
  alignas(16) float m_root_bound[6][4] = {};
  /// Sets m_root_bound from the root's box.
  void set_root_box(const std::array<float, 6>& box);
  uint32_t m_root_link = kNoLink;
  uint32_t m_stamp = 0;  ///< even, one per fill: the nodes evaluated for this frame hold it
  const TreeFrame* m_frame = nullptr;  ///< the frame filled (it must outlive the queries)
  /// Per vertex, its coordinates this frame rounded to the nearest floats (x, y, z and one
  /// unused lane): a + b (t - o) for the kinetic trees, whose sides are such floats moved outward
  /// by margin() when a node is evaluated; the bottom-up tree's positions. The triangle tests'
  /// rejection reads them too. Evaluated for every vertex in one sequential pass, as the
  /// realizers of the nodes a frame visits are spread over all. 16 bytes a vertex, not a padded
  /// low and high corner's 32: the pass writes half as much and more of it is still in cache
  /// when the nodes read it.
  struct alignas(16) VertexPoint {
    float c[4];
  };
  std::vector<VertexPoint> m_vertex_point;
  /// The per-frame part of the margin: a float >= (pad + 1e-30) (1 + 2^-20).
  float m_margin_pad = 0;
};

/// The nearest hit through the frame's boxes: the same answer as closest_hit of tree_query.h on
/// the tree they were filled from. Any-hit queries: frame_occluded (frame_occlusion.h).
[[nodiscard]] std::optional<TreeHit> frame_closest_hit(const FrameBoxes& boxes,
                                                       const TreeRay& ray);

}  // namespace kinray
