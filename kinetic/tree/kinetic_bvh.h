#pragma once
// The kinetic AABB tree and the kinetic BoxTree of Zachmann and Weller (VRCIA 2006; docs/design.md,
// "Kinetic AABB tree and kinetic BoxTree"). The tree's shape is built once (binned SAH) and kept;
// each node side (an axis and max or min) stores its realizing vertex, the vertex of the subtree
// that is extreme there. Certificates are linear on a flightplan segment:
//   - a leaf side: the realizer is beyond the triangle's two other vertices (leaf event),
//   - an inner side: the realizer, one child's, is beyond the other child's (tree event),
// and a failure swaps the realizer and climbs while the parents' realizers change. At a key every
// certificate of the mesh's subtrees is recomputed (flightplan update); a mesh appearing or
// disappearing attaches or detaches its leaves. Between events nothing is computed: a box at time
// t is its realizers' coordinates at t.
//
// The AABB tree tracks all six sides of every node. The BoxTree splits each inner node along one
// axis and stores its left child's max and its right child's min there; a node then tracks only
// the sides its ancestors' planes need, so it never has more certificates than the AABB tree.
#include <array>
#include <bit>
#include <cstdint>
#include <functional>
#include <vector>

#include "kinetic/core/simulator.h"
#include "kinetic/tree/bvh_topology.h"
#include "kinetic/tree/tree_meshes.h"
#include "kinetic/tree/tree_query.h"
#include "kinetic/tree/tree_stats.h"

namespace kinray {

enum class TreeShape { aabb, boxtree };

/// Node side s = 2 axis + (0: max, 1: min).
[[nodiscard]] constexpr int side_axis(int s) {
  return s >> 1;
}
[[nodiscard]] constexpr int side_sign(int s) {
  return (s & 1) != 0 ? -1 : 1;
}
[[nodiscard]] constexpr int side_of(int axis, bool max) {
  return 2 * axis + (max ? 0 : 1);
}

class KineticBvh {
 public:
  struct Config {
    TreeShape shape = TreeShape::aabb;
    bool audit = false;  ///< audit() after every advance_to (tests)
    /// Lazy key pass (the separation list's trees): at a key of a moving mesh every node above its
    /// leaves falls asleep (no certificate, no event) and keeps its segment box; a reader wakes the
    /// nodes it reads (wake), each with its whole subtree, as the eager key pass would have
    /// computed them. Nodes nobody reads in a segment cost one pass over their boxes.
    bool lazy = false;
  };

  /// Builds the tree at time t over the meshes' triangles (present or not).
  KineticBvh(std::vector<FlightplanMesh> meshes, double t, const Config& config);

  /// Processes every event up to t (t never decreases).
  void advance_to(double t);
  [[nodiscard]] double now() const { return m_sim.now(); }
  /// Time of the next scheduled event (+inf when none): lets a structure built on the tree (the
  /// kinetic separation list) interleave its own events with the tree's in time order.
  [[nodiscard]] double next_event_time() const { return m_sim.next_event_time(); }

  /// Called with (node, side) whenever the realizer of a node side changes (tree and leaf events,
  /// keys, appearance). The observer must stay valid while the tree advances.
  using RealizerObserver = std::function<void(uint32_t node, int side)>;
  void add_realizer_observer(RealizerObserver observer) {
    m_observers.push_back(std::move(observer));
  }

  /// At a time strictly between events (after the last one processed): every tracked side's value
  /// equals the extreme recomputed from the node's leaves, every certificate holds, and an event
  /// is scheduled exactly when the certificate fails within its segment (KINRAY_CHECK).
  void audit() const;

  [[nodiscard]] const TreeMeshes& meshes() const { return m_meshes; }
  [[nodiscard]] const BvhTopology& topology() const { return m_topology; }
  [[nodiscard]] TreeShape shape() const { return m_config.shape; }
  /// The vertex realizing side s of a node (kNoVertex when untracked or the node is empty).
  [[nodiscard]] uint32_t realizer(uint32_t node, int s) const {
    return m_node[node].realizer[size_t(s)];
  }
  /// Lazy trees: the node's realizers and certificates are current (an awake node's subtree is
  /// awake). Eager trees: always.
  [[nodiscard]] bool awake(uint32_t node) const { return m_node[node].asleep == 0; }
  /// Lazy trees: computes the node and every sleeping node below it now, children first, as the
  /// key pass computes them (the decision from the two keys' positions where it holds, update_side
  /// elsewhere); the observers hear of every realizer that changed.
  void wake(uint32_t node);
  [[nodiscard]] bool lazy() const { return m_config.lazy; }
  /// Lazy trees: the box of every key position of the node's leaves on their meshes' current
  /// segments, which holds the node's box at every time of the segment (the motion is linear).
  [[nodiscard]] const Aabb& segment_box(uint32_t node) const { return m_segment_box[node]; }
  /// Some triangle below the node is present now.
  [[nodiscard]] bool active(uint32_t node) const { return m_node[node].active != 0; }
  /// How many times some node's presence has changed since the build: a copy of the realizers
  /// kept current by an observer (FrameBoxes) reads the presence again when this moved.
  [[nodiscard]] uint64_t presence_changes() const { return m_presence_changes; }
  /// Side s of the node at t, from its realizer (t within the current segments).
  [[nodiscard]] double side_value(uint32_t node, int s, double t) const {
    return m_meshes.coordinate(m_node[node].realizer[size_t(s)], side_axis(s), t);
  }

  /// The queries' boxes (tree_query.h) at the frame's time, from the realizers. AABB tree: a
  /// node's own six sides. BoxTree: the root is the box of every key position and a child is its
  /// parent's box cut by the sides it tracks: the parent's plane (the left child's max or the right
  /// child's min along the split axis) and the planes its other ancestors need, which are its own
  /// extremes too.
  [[nodiscard]] Aabb root_box(const TreeFrame& frame) const {
    if (m_topology.nodes.empty() || !m_node[0].active) return Aabb{};
    if (m_config.shape == TreeShape::boxtree) {
      Aabb all;  // no side of the root is tracked: the box of the whole shot bounds it
      all.lo = m_meshes.shot_lo().array() - frame.pad;
      all.hi = m_meshes.shot_hi().array() + frame.pad;
      return all;
    }
    return own_box(0, frame);
  }
  void child_boxes(const BvhNode& n, const Aabb& box, const TreeFrame& frame, Aabb& left,
                   Aabb& right) const {
    if (m_config.shape == TreeShape::aabb) {
      left = own_box(n.left, frame);
      right = own_box(n.right, frame);
      return;
    }
    left = right = box;
    tighten(n.left, frame, left);
    tighten(n.right, frame, right);
  }

  /// Wall time spent in mesh events (keys, appearances, disappearances: the pass over every node
  /// above the mesh's leaves), part of the time advance_to took: how an update
  /// splits between keys and certificate failures.
  [[nodiscard]] double mesh_event_seconds() const { return m_mesh_event_seconds; }
  /// The margin by which the key pass settles a certificate from its two key positions
  /// (kinetic_bvh_keys.cpp): far above the rounding of a + b (t - o) against the key positions.
  [[nodiscard]] double key_margin() const { return m_key_margin; }
  /// Counters, with the live certificates counted now.
  [[nodiscard]] TreeStats stats() const;
  [[nodiscard]] size_t memory_bytes() const;

 private:
  /// Tests corrupt a tree's state through this to see the audit report it.
  friend struct KineticBvhTestAccess;
  static constexpr uint64_t kMeshEvent = uint64_t{1} << 63;
  enum EventKind : uint32_t { kMeshKind = 0, kLeafKind = 1, kTreeKind = 2 };

  /// Recomputes side s of the node just after now and reschedules its certificate; returns
  /// whether its realizer changed.
  bool update_side(uint32_t node, int s);
  void tighten(uint32_t node, const TreeFrame& frame, Aabb& b) const {
    if (!m_node[node].active) {
      b = Aabb{};
      return;
    }
    for (int s = 0; s < 6; ++s) {
      if (((m_node[node].sides >> s) & 1) == 0) continue;
      const int a = side_axis(s);
      const double v = side_value(node, s, frame.t);
      if (side_sign(s) > 0)
        b.hi[a] = std::min(b.hi[a], v + frame.pad);
      else
        b.lo[a] = std::max(b.lo[a], v - frame.pad);
    }
  }
  [[nodiscard]] Aabb own_box(uint32_t node, const TreeFrame& frame) const {
    Aabb b;
    if (!m_node[node].active) return b;
    for (int a = 0; a < 3; ++a) {
      b.hi[a] = side_value(node, side_of(a, true), frame.t) + frame.pad;
      b.lo[a] = side_value(node, side_of(a, false), frame.t) - frame.pad;
    }
    return b;
  }
  void schedule(uint32_t node, int s, double time);
  /// At a key of a moving mesh (kinetic_bvh_keys.cpp): the tracked sides of the node whose realizer
  /// provably stays through the new segment, decided from the key positions alone and settled (no
  /// failure time, no event); the others are left to update_side.
  uint8_t settle_at_key(uint32_t node);
  /// The sides `open` of a node (tracked, active, realized) that no margin settled, settled when
  /// the realizer ties with each competitor at both keys and has the lower id: identically zero
  /// certificates, whose side update_side's tie-break keeps (a flat region). Fills `live` as
  /// settle_at_key does; out of line, after its loop, so that the common case does not pay.
  uint8_t settle_ties(uint32_t node, uint8_t open, std::array<uint8_t, 6>& live) const;
  /// Those sides keep their realizer with `live` certificates each and no event.
  void settle_sides(uint32_t node, uint8_t sides, const std::array<uint8_t, 6>& live);
  /// The key pass's work on one node (settle_at_key where the motion is linear, update_side for
  /// the rest); returns how many sides the keys settled.
  uint32_t refresh_node(uint32_t node, bool moving);
  /// Lazy trees at a key: the node's events cancelled, its certificates dropped.
  void sleep(uint32_t node);
  void set_segment_box(uint32_t node);
  void handle(const EventKey& key, uint64_t payload);
  void handle_mesh(uint32_t m);
  void schedule_mesh(uint32_t m);
  /// Recomputes every node above mesh m's leaves, children first.
  void refresh_mesh(uint32_t m);
  /// A side recomputed from a node's leaves by the audit: the realizing vertex in the tree's order
  /// and the largest sign * coordinate of the leaves' vertices.
  struct AuditExtreme {
    uint32_t vertex = kNoVertex;
    double largest = -std::numeric_limits<double>::infinity();
  };
  void audit_node(uint32_t node, double t, std::vector<std::array<AuditExtreme, 6>>& extreme) const;
  [[nodiscard]] uint64_t live_certificates() const;

  Config m_config;
  TreeMeshes m_meshes;
  BvhTopology m_topology;
  Simulator m_sim;
  /// What an event or a key reads and writes of a node, in one cache line rather than five arrays
  /// (realizers, event handles, live counts, tracked sides, presence). Measured: instructions
  /// -1%, wall time within the noise (docs/kinetic_trees.md, "Limits"); kept as the simpler
  /// layout.
  struct alignas(64) NodeState {
    std::array<uint32_t, 6> realizer{kNoVertex, kNoVertex, kNoVertex,
                                     kNoVertex, kNoVertex, kNoVertex};
    std::array<EventHandle, 6> event{kNoEvent, kNoEvent, kNoEvent, kNoEvent, kNoEvent, kNoEvent};
    std::array<uint8_t, 6> live{};  ///< per side: its live certificates (leaf 0-2, inner 0-1)
    uint8_t sides = 0;              ///< bit s set when side s is tracked
    uint8_t active = 0;             ///< some triangle below the node is present
    /// Bit s set when the last key pass settled side s by the margin at both keys of the current
    /// segment, and nothing has recomputed it or changed a child's realizer since: the realizer
    /// and its competitors are the ones it compared. At the next key the segment's start key is
    /// the end key it compared, so the pass compares at the end key only.
    uint8_t verified = 0;
    uint8_t asleep = 0;  ///< lazy trees: asleep since a key (Config::lazy)
  };
  static_assert(sizeof(NodeState) == 64);
  std::vector<NodeState> m_node;
  std::vector<Aabb> m_segment_box;  ///< per node, lazy trees only
  std::vector<uint32_t> m_wake_stack;
  /// per node: the mesh every leaf below it belongs to (kMixedMeshes when there are several): a
  /// key of that mesh finds all the node's realizers and competitors among its own vertices
  std::vector<uint32_t> m_node_mesh;
  static constexpr uint32_t kMixedMeshes = ~0u;
  std::vector<std::array<uint32_t, 3>>
      m_leaf_vertices;  ///< per node: a leaf's triangle, in node order
  uint64_t m_live_total = 0;
  double m_key_margin = 0;  ///< far above the rounding of a + b (t - o) against the key positions
  std::vector<uint32_t> m_mesh_node_begin, m_mesh_nodes;  ///< per mesh: its nodes, descending
  std::vector<EventHandle> m_mesh_event;
  TreeStats m_stats;
  double m_mesh_event_seconds = 0;
  std::vector<RealizerObserver> m_observers;
  uint64_t m_presence_changes = 0;
};

}  // namespace kinray
