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

// X(member, "stats key") of TreeStats, by the section of --stats they are written in
// (kinetic/core/counters.h): the top level, "certificates", and "tree" (the tree's shape).
#define KINRAY_TREE_COUNTERS(X)                                                                 \
  X(events_external, "events_external") /* events that changed some node's realizing vertex */  \
  X(events_internal, "events_internal") /* the others (key updates, rounding-level failures) */ \
  X(realizer_changes,                                                                           \
    "realizer_changes")         /* node sides whose realizer changed (propagation too) */       \
  X(nodes_woken, "nodes_woken") /* lazy trees: nodes computed when read after a key */
#define KINRAY_TREE_CERTIFICATE_COUNTERS(X)                                                    \
  X(certificates_live, "live")            /* now (leaf sides count two, inner sides one) */     \
  X(certificates_live_max, "live_max")    /* the largest certificates_live seen at a frame */  \
  X(certificates_computed, "computed")    /* every certificate (re)computation */              \
  X(certificates_by_keys, "decided_at_keys") /* of which decided at a key from two positions */ \
  X(scheduled_events, "scheduled")        /* certificates with a failure in their segment */
#define KINRAY_TREE_SHAPE_COUNTERS(X)                                                          \
  X(nodes, "nodes")                                                                            \
  X(height, "height")                                                                          \
  X(node_sides, "node_sides")             /* node sides tracked */                             \
  X(triangles, "triangles")                                                                    \
  X(triangles_present, "triangles_present")

struct TreeStats {
  TreeEventCounts events;
  KINRAY_TREE_COUNTERS(KINRAY_COUNTER_FIELD)
  KINRAY_TREE_CERTIFICATE_COUNTERS(KINRAY_COUNTER_FIELD)
  KINRAY_TREE_SHAPE_COUNTERS(KINRAY_COUNTER_FIELD)

  /// visit("stats key", value) for the counters of the top level, of "certificates", of "tree".
  KINRAY_COUNTER_SECTION(for_each_counter, KINRAY_TREE_COUNTERS)
  KINRAY_COUNTER_SECTION(for_each_certificate_counter, KINRAY_TREE_CERTIFICATE_COUNTERS)
  KINRAY_COUNTER_SECTION(for_each_shape_counter, KINRAY_TREE_SHAPE_COUNTERS)
};

}  // namespace kinray
