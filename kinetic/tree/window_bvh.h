#pragma once
// Rays at any time of a time window: motion blur's shadow rays (renderer/motion_blur/). The
// kinetic trees answer at one time and only move forward, while a shutter window's shadow rays
// come at every quadrature node and bisection time of every pixel, in no order. This tree keeps
// one shape (the kinetic trees' builder, binned SAH, run on the first window) and, per window,
// boxes that bound each triangle over each of four equal parts of the window: a vertex moves
// linearly between its mesh's keys, so its positions at the part's ends and at the keys inside
// span its path. A moving camera moves every triangle, and boxes over a quarter of the window
// are the tighter for it (the BART kitchen's blurred shadows: 7% less time than boxes over the
// whole window; eighths gained nothing more). A ray at time t descends through the boxes of its
// part and meets the triangles placed at t as
// FlightplanMesh::position places them (the Embree reference's arithmetic), so its answer is the
// exact one at t; the boxes only decide how much of the tree it visits. This is Embree's own
// approach to motion blur (boxes over the shutter, primitives at the ray's time), with the
// window's sweep a pass over the vertices and the nodes, not a build.
#include <array>
#include <cstdint>
#include <vector>

#include "kinetic/tree/bvh_topology.h"
#include "kinetic/tree/tree_meshes.h"
#include "kinetic/tree/tree_query.h"

namespace kinray {

class WindowBvh {
 public:
  /// The spans of `meshes` must outlive this object.
  explicit WindowBvh(std::vector<FlightplanMesh> meshes);

  /// Boxes over [open, close] (open <= close): every triangle of a mesh present at some time of
  /// the window, over its path through the window. The first call builds the shape.
  void sweep(double open, double close);
  /// Whether the ray meets a triangle present at time t (t in the last swept window), other
  /// than ray.skip, at s_min < s < s_max. Thread-safe between sweeps.
  [[nodiscard]] bool occluded(const TreeRay& ray, double t) const {
    return occluder(ray, t) != kNoNode;
  }
  /// The same question answered by a triangle that meets the ray (kNoNode: none does), tried
  /// first with `hint` (a triangle or kNoNode): a shadow ray of the next instant of a pixel is
  /// mostly blocked by the triangle that blocked the last, and one test then spares the descent.
  [[nodiscard]] uint32_t occluder(const TreeRay& ray, double t, uint32_t hint = kNoNode) const;
  /// The same answer from every triangle, without the tree (tests).
  [[nodiscard]] bool occluded_brute_force(const TreeRay& ray, double t) const;

  [[nodiscard]] const TreeMeshes& meshes() const { return m_meshes; }
  [[nodiscard]] const BvhTopology& topology() const { return m_topology; }
  [[nodiscard]] uint64_t sweeps() const { return m_sweeps; }

 private:
  /// A ray's last mesh and its key blend at the ray's time: the triangles a ray tests mostly
  /// belong to a few meshes, and finding the blend is a search of the mesh's keys.
  struct MeshAtTime {
    uint32_t mesh = kNoNode;
    bool present = false;
    FlightplanMesh::KeyBlend blend;
  };
  /// Triangle tri at time t (present at t), hit by the ray within (s_min, s_max)?
  [[nodiscard]] bool hits(uint32_t tri, const TreeRay& ray, double t, MeshAtTime& at) const;

  TreeMeshes m_meshes;
  BvhTopology m_topology;
  /// A wide node as the traversal reads it: its four children's boxes over a stratum of the
  /// window, rounded outward to floats (row r, slot k; an unused slot empty), side by side for
  /// wide_slab_test.h's one test of all four, and each slot's link: a wide node, kLeaf |
  /// triangle, or kNoNode.
  struct alignas(64) Node {
    float bound[6][4];
    std::array<uint32_t, 4> link;
  };
  static constexpr uint32_t kLeaf = 1u << 31;
  /// The window's equal parts, each with its own boxes.
  static constexpr size_t kStrata = 4;

  /// m_vertex_boxes over [open, close].
  void sweep_vertices(double open, double close);
  /// `nodes` over [open, close], from m_vertex_boxes (through m_boxes).
  void sweep_nodes(double open, double close, std::vector<Node>& nodes);

  std::vector<Aabb> m_boxes;         ///< per node, over the stratum last swept
  FourWideTopology m_wide;           ///< the shape, four children per node
  std::array<std::vector<Node>, kStrata> m_strata;    ///< per stratum, its wide nodes
  std::array<double, kStrata + 1> m_stratum_times{};  ///< the strata's ends, in time order
  uint32_t m_root_link = kNoNode;    ///< wide node 0, a lone triangle's leaf, or kNoNode
  std::vector<Aabb> m_vertex_boxes;  ///< per global vertex: its path over the stratum last swept
  double m_open = 0, m_close = 0;
  uint64_t m_sweeps = 0;
};

}  // namespace kinray
