#pragma once
// The corner steps of one mesh edge, followed once and shared by the records of the triangles on
// either side of it: along each row line strictly between its end points' rows, where its edge
// function changes sign among the line's corners. A triangle before the eye reads exactly these
// (the two edges that cross each of its row lines) and holds a copy of them, so that one corner
// crossed by an edge is one event for both of its triangles. The edge function is taken in the
// edge's own direction (its lower global vertex id first); a triangle that runs the edge the
// other way reads every sign negated.
#include <cstdint>
#include <vector>

#include "kinetic/core/event_queue.h"
#include "kinetic/squares/pixel_line_signs.h"

namespace kinray {

struct EdgeStep {
  CornerStep step;
  EventHandle event = kNoEvent;
};

struct EdgeTracker {
  uint32_t users = 0;           ///< records (kFront) that read the steps
  int line_begin = 0;           ///< the first row line followed
  std::vector<EdgeStep> lines;  ///< one per row line from line_begin on
};

}  // namespace kinray
