#pragma once
// Counters of the per-square sets (pbrt STAT_COUNTER style). Every event count is set by the
// geometry and the motion alone, never by the frames read out: an edge line passing a square
// corner (once per edge, or per triangle across the eye plane), a vertex crossing a column line or
// a row line, a vertex crossing the eye plane, a plane sweeping the eye or an edge turning
// horizontal, a key, a mesh appearing or disappearing.
#include <cstdint>

#include "kinetic/core/counters.h"

namespace kinray {

// X(member, "stats key"), one line per kind of event.
#define KINRAY_SQUARE_EVENT_KINDS(X)                                                  \
  X(corner, "corner")         /* an edge line passed a square corner */               \
  X(side, "side")             /* a vertex crossed a column line within its row */     \
  X(row, "row")               /* a vertex changed row (its records laid out again) */ \
  X(rebuild, "rebuild")       /* a vertex changed eye side, O or n_x changed sign */  \
  X(flightplan, "flightplan") /* a mesh reached a key (certificates recomputed) */    \
  X(insert, "insert")         /* a mesh appeared after the start */                   \
  X(remove, "delete")         /* a mesh disappeared */

struct SquareEventCounts {
  KINRAY_EVENT_COUNTERS(SquareEventCounts, KINRAY_SQUARE_EVENT_KINDS)
};

// X(member, "stats key").
#define KINRAY_SQUARE_COUNTERS(X)                                                                  \
  X(certificates_scheduled, "certificates_scheduled") /* every failure time computed */            \
  X(spurious, "spurious")                             /* events after which nothing had changed */ \
  X(square_changes, "square_changes")     /* a triangle into or out of a pixel's set */            \
  X(records_built, "records_built")       /* triangle records built or rebuilt */                  \
  X(records_reshaped, "records_reshaped") /* records laid out again after a vertex's row */        \
  X(pixel_entries, "pixel_entries")       /* now: triangles held over all pixels */                \
  X(triangles_front, "triangles_front")   /* now: records of triangles wholly before the eye */    \
  X(triangles_straddling, "triangles_straddling") /* now: records across the eye plane */          \
  X(vertices_followed, "vertices_followed")       /* now: vertices whose cells records read */     \
  X(edges_followed, "edges_followed")             /* now: edges whose steps records read */        \
  X(events_pending, "events_pending")             /* now: events in the queue (compactness) */

struct SquareStats {
  KINRAY_COUNTERS_WITH_EVENTS(SquareStats, SquareEventCounts, KINRAY_SQUARE_COUNTERS)
};

}  // namespace kinray
