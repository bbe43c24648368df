#pragma once
// Counters of the kinetic grid (pbrt STAT_COUNTER style), summed over bands. Every event count
// is defined by the geometry and the motion alone (a boundary crossing a column centre, a vertex
// crossing a row plane, a swap in a pixel, ...), so it depends neither on how many frames are
// read out nor on how many bands the rows are split into.
#include <cstdint>

#include "kinetic/core/counters.h"

namespace kinray {

// X(member, "stats key"), one line per kind of event.
#define KINRAY_GRID_EVENT_KINDS(X)                                                          \
  X(boundary, "boundary")       /* a boundary crossed a column centre */                    \
  X(vertex_row, "vertex_row")   /* a vertex crossed a row plane (one per vertex and row) */ \
  X(orientation, "orientation") /* a triangle's plane swept through the eye (per band) */  \
  X(swap, "swap")               /* two triangles changed depth order in a pixel */          \
  X(flightplan, "flightplan")   /* a mesh reached a key (one per mesh and key) */           \
  X(insert, "insert")           /* a mesh appeared after the start */                       \
  X(remove, "delete")           /* a mesh disappeared */

struct GridEventCounts {
  KINRAY_EVENT_COUNTERS(GridEventCounts, KINRAY_GRID_EVENT_KINDS)
};

// X(member, "stats key"). Gauges ("now") are summed over bands like the counts.
#define KINRAY_GRID_COUNTERS(X)                                                                  \
  X(events_external, "events_external")   /* events that changed some pixel's front */           \
  X(events_internal, "events_internal")   /* the others */                                       \
  X(spurious, "spurious")                 /* certificate failures that were rounding */          \
  X(renewals, "renewals")                 /* depth certificates renewed at a key, or rechecked */ \
  X(exact_deferred, "exact_deferred")     /* exact depth searches put off to a recheck */        \
  X(coverage_changes, "coverage_changes") /* a triangle into / out of a pixel's order */         \
  X(records_born, "records_born")                                                                \
  X(records_died, "records_died")                                                                \
  X(reties, "reties")                                                                            \
  X(row_rebuilds, "row_rebuilds")               /* records rebuilt (orientation, degenerate) */  \
  X(degenerate_rebuilds, "degenerate_rebuilds") /* of which: inconsistent signs at once */       \
  X(certificates_computed, "certificates_computed") /* every (re)computation, depth too */       \
  X(certificates_live, "certificates_live")         /* now */                                    \
  X(certificates_live_max, "certificates_live_max") /* sum over bands of each one's most */      \
  X(records, "records")                             /* live (triangle, row) records */           \
  X(pixel_entries, "pixel_entries")                 /* triangles held in the per-pixel orders */ \
  X(triangles_present, "triangles_present")                                                      \
  X(meshes_culling, "meshes_culling")         /* present meshes with back-face culling, now */   \
  X(triangles_culled, "triangles_culled")     /* of theirs: facing away now, without records */  \
  X(memory_bytes, "memory_bytes")             /* now */                                          \
  X(pixel_memory_bytes, "pixel_memory_bytes") /* of which: the per-pixel orders */               \
  X(edge_normal_bytes, "edge_normal_bytes")   /* of which: the edge normals' pages written */

struct GridStats {
  KINRAY_COUNTERS_WITH_EVENTS(GridStats, GridEventCounts, KINRAY_GRID_COUNTERS)
};

}  // namespace kinray
