#pragma once
// One triangle's record in the per-square sets: where its region R stands among the pixel lines,
// as signs only, and the squares that follow from them. Per strip j (the row of pixels between row
// lines j and j + 1) the squares R overlaps are the columns that meet the x-extent of R within the
// strip; R within the strip is convex, so that extent is the hull of R's intersections with the
// two row lines and of R's vertices inside the strip, and each of those is known to a column cell
// from the signs: a vertex by its column cell (X - x Z), an intersection with a row line by where
// the edge functions change sign along the line's corners (E at a corner). Nothing is measured.
//   - A triangle wholly before the eye (kFront) has R its projection: each row line strictly
//     between its vertices' rows is crossed by exactly two edges, at the two ends of R's segment
//     on it, and only those two are read (copies of the edges' own steps, edge_steps.h).
//   - A triangle across the eye plane (kStraddling) has R unbounded (R's vertices are the
//     projections of its vertices before the eye): on every row line of the image R is the
//     intersection of the three edges' half-lines, each read off its corner signs with sign(O)
//     and the sign of n_x (E at the corner at infinity (1, 0, 0), watched too: it tells on which
//     side of the image an edge's crossing lies when every corner of the line has one sign, which
//     matters to the hull when R's part of the line lies off the image). When two of them end in
//     the same column their order decides, and it is a vertex's side of the row line (the two
//     edge lines meet at the projection of their shared vertex).
//   - A triangle behind the eye, or degenerate on the whole key segment, has R empty.
// Whatever is off the image is clamped to cell -1 or the last cell, so off-screen motion emits
// no events.
#include <array>
#include <cstdint>
#include <vector>

#include "kinetic/core/event_queue.h"
#include "kinetic/squares/pixel_line_signs.h"
#include "kinetic/squares/square_lattice.h"
#include "kinetic/squares/vertex_cells.h"

namespace kinray {

/// One edge function along one row line: the step of its signs over the line's corners, in the
/// triangle's own direction of the edge.
struct EdgeOnLine {
  int16_t line = 0;
  int8_t edge = 0;  ///< from vertex edge to vertex (edge + 1) % 3 (kEdgeStart / kEdgeEnd)
  CornerStep step;
  EventHandle event = kNoEvent;  ///< kStraddling only (kFront holds a copy of its edge's step)
};

/// Columns lo..hi (empty when lo > hi); -1 and width stand for "off the image" before clamping.
struct ColumnRange {
  int lo = 1, hi = 0;
  [[nodiscard]] bool empty() const { return lo > hi; }
  [[nodiscard]] bool contains(int c) const { return c >= lo && c <= hi; }
  void hull(const ColumnRange& o) {
    if (o.empty()) return;
    if (empty()) {
      *this = o;
    } else {
      lo = lo < o.lo ? lo : o.lo;
      hi = hi > o.hi ? hi : o.hi;
    }
  }
};

struct TriangleRecord {
  enum class Mode : uint8_t { kAbsent, kEmpty, kBehind, kFront, kStraddling };
  Mode mode = Mode::kAbsent;
  int8_t orientation = 0;  ///< sign of O (kStraddling: watched)
  EventHandle orientation_event = kNoEvent;
  /// kStraddling: per edge, the sign of n_x = (p x q).x, watched.
  std::array<int8_t, 3> nx_sign{};
  std::array<EventHandle, 3> nx_events{kNoEvent, kNoEvent, kNoEvent};
  std::array<VertexCells, 3> vertices;  ///< copies of the vertices' own (vertex_cells.h)
  int line_begin = 0;               ///< first row line followed
  int edges_per_line = 0;           ///< 2 (kFront) or 3 (kStraddling)
  std::vector<EdgeOnLine> lines;    ///< edges_per_line per row line from line_begin on
  int strip_begin = 0;              ///< first strip held
  std::vector<ColumnRange> strips;  ///< per strip from strip_begin on, clamped to the image

  [[nodiscard]] int line_end() const {
    return edges_per_line == 0 ? line_begin : line_begin + int(lines.size()) / edges_per_line;
  }
  [[nodiscard]] ColumnRange strip(int j) const {
    return j >= strip_begin && j < strip_begin + int(strips.size())
               ? strips[size_t(j - strip_begin)]
               : ColumnRange{};
  }
};

/// The columns R meets on row line k, unclamped (-1..width), from the record's signs.
[[nodiscard]] ColumnRange line_columns(const TriangleRecord& rec, int k, int width);

/// The columns R overlaps in strip j, clamped to the image: the hull of R on row lines j and
/// j + 1 and of the projections of R's vertices in the strip.
[[nodiscard]] ColumnRange strip_columns(const TriangleRecord& rec, int j, int width);

}  // namespace kinray
