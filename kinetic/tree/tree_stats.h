#pragma once
// Counters of the kinetic trees (pbrt STAT_COUNTER style). Every event count is set by the motion
// alone: a realizing vertex overtaken by another (leaf and tree events), a mesh reaching a key or
// appearing or disappearing; none depends on how many frames are queried.
#include <cstdint>

#include "kinetic/core/counters.h"

namespace kinray {

// X(member, "stats key"), one line per kind of event.
#define KINRAY_TREE_EVENT_KINDS(X)                                                            \
  X(leaf, "leaf")             /* a triangle's realizing vertex on a node side was overtaken */ \
  X(tree, "tree")             /* an inner node's realizer was overtaken by the other child's */ \
  X(flightplan, "flightplan") /* a mesh reached a key: its certificates recomputed */         \
  X(insert, "insert")         /* a mesh appeared: its leaves attached */                      \
  X(remove, "delete")         /* a mesh disappeared: its leaves detached */

struct TreeEventCounts {
  KINRAY_EVENT_COUNTERS(TreeEventCounts, KINRAY_TREE_EVENT_KINDS)
  /// Certificate failures only (leaf and tree events): what moves with the geometry.
  [[nodiscard]] uint64_t failures() const { return leaf + tree; }
};

struct TreeStats {
  TreeEventCounts events;
  uint64_t events_external = 0;        ///< events that changed some node's realizing vertex
  uint64_t events_internal = 0;        ///< the others (key updates, rounding-level failures)
  uint64_t realizer_changes = 0;       ///< node sides whose realizer changed (incl. propagation)
  uint64_t certificates_computed = 0;  ///< every certificate (re)computation
  uint64_t certificates_by_keys = 0;   ///< of which decided at a key from the two key positions
  uint64_t certificates_live = 0;      ///< now (leaf sides count two, inner sides one)
  uint64_t certificates_live_max = 0;  ///< the largest certificates_live seen at a frame
  uint64_t scheduled_events = 0;       ///< certificates with a failure in their segment, now
  uint64_t nodes = 0, height = 0, node_sides = 0;  ///< the tree; node sides tracked
  uint64_t triangles = 0, triangles_present = 0;
};

}  // namespace kinray
