#pragma once
// Where a vertex's projection lies among the pixel lines, followed once per vertex and shared by
// the records of every triangle around it (a vertex of a closed mesh has about six): its side of
// the eye plane always, and the row and column cells of its projection while some record that
// reads them (a triangle before the eye or across its plane) uses it. Off the image the cells are
// clamped (-1, or the last line's index), so that off-screen motion emits no events.
#include <cstdint>

#include "kinetic/core/event_queue.h"

namespace kinray {

inline constexpr int16_t kNoCell = INT16_MIN;  ///< a cell nobody follows

/// A vertex's side of the eye plane and the cells of its projection: c when it lies after lines
/// 0..c (right of column lines, below row lines) and before the others (pixel_line_signs.h).
/// Records hold a copy, kept equal to the vertex's own.
struct VertexCells {
  int8_t z_sign = 1;
  int16_t row = kNoCell;     ///< -1..height
  int16_t column = kNoCell;  ///< -1..width, before the eye only
  friend bool operator==(const VertexCells&, const VertexCells&) = default;
};

/// A vertex's cells, how many records read them, and one event for all its certificates.
struct VertexTracker {
  VertexCells cells;
  uint32_t users = 0;  ///< records (kFront, kStraddling) that read the cells
  EventHandle event = kNoEvent;
};

}  // namespace kinray
