#include "kinetic/squares/triangle_footprint.h"

#include <algorithm>

namespace kinray {

namespace {

using Mode = TriangleRecord::Mode;

/// The column where a front triangle's edge crosses row line k: its step, or off the image on
/// the side its signs say. Along the line E's sign left of the crossing is -sign(n_x), and with
/// both ends before the eye n_x > 0 exactly when the edge's start lies above the line: the
/// crossing is right of the image when every corner has the left sign.
int front_crossing(const TriangleRecord& rec, const EdgeOnLine& e, int k, int width) {
  if (e.step.count <= width) return e.step.count - 1;
  const bool start_above = rec.vertices[size_t(kEdgeStart[e.edge])].row < k;
  const int left_sign = start_above ? -1 : 1;
  return e.step.first == left_sign ? width : -1;
}

/// For two edges whose crossings of row line k lie in one column (or off the image on one side),
/// e1 bounding R's part of the line from the left ([a, inf)) and e2 from the right ((-inf, b]):
/// whether a <= b. The point a is n1 x r (r = (0, 1, -y_k)) divided by its z, n1.x; its edge
/// function for e2 is r . (n2 x n1) = +-O (Y_q - y_k Z_q), q the shared vertex (+ when e1 starts
/// at q), so sign(O) cancels and a <= b is a sign of q's side of the line, which the record
/// follows, times that of n1.x.
bool ordered(const TriangleRecord& rec, int e1, int e2, int k) {
  const bool e1_starts_at_q = kEdgeStart[e1] == kEdgeEnd[e2];
  const int q = e1_starts_at_q ? kEdgeStart[e1] : kEdgeEnd[e1];
  const VertexCells& v = rec.vertices[size_t(q)];
  const int side = v.row >= k ? -v.z_sign : v.z_sign;  // sign of Y_q - y_k Z_q
  return (e1_starts_at_q ? 1 : -1) * side * rec.nx_sign[size_t(e1)] > 0;
}

ColumnRange straddling_columns(const TriangleRecord& rec, const EdgeOnLine* edges, int k,
                               int width) {
  // Each edge's half-line: its end's column (-1 or width when off the image: all corners have
  // the sign of +inf, n_x's, when the end lies left of them) and whether R is to its right.
  std::array<int, 3> end{};
  std::array<bool, 3> inside_right{};
  int lo = -2, hi = width + 1;  // -2, width + 1: unbounded
  for (int a = 0; a < 3; ++a) {
    const EdgeOnLine& e = edges[a];
    const int nx = rec.nx_sign[size_t(e.edge)];
    end[size_t(a)] = e.step.count <= width ? e.step.count - 1 : (e.step.first == nx ? -1 : width);
    inside_right[size_t(a)] = nx == rec.orientation;
    if (inside_right[size_t(a)])
      lo = std::max(lo, end[size_t(a)]);
    else
      hi = std::min(hi, end[size_t(a)]);
  }
  if (lo > hi) return {};
  if (lo == hi) {
    // Both ends in one column: every left end must lie before every right end there.
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b)
        if (inside_right[size_t(a)] && !inside_right[size_t(b)] && end[size_t(a)] == lo &&
            end[size_t(b)] == lo && !ordered(rec, edges[a].edge, edges[b].edge, k))
          return {};
  }
  return {std::max(lo, -1), std::min(hi, width)};
}

}  // namespace

ColumnRange line_columns(const TriangleRecord& rec, int k, int width) {
  if (k < rec.line_begin || k >= rec.line_end()) return {};
  const EdgeOnLine* edges = &rec.lines[size_t((k - rec.line_begin) * rec.edges_per_line)];
  if (rec.mode == Mode::kStraddling) return straddling_columns(rec, edges, k, width);
  const int a = front_crossing(rec, edges[0], k, width),
            b = front_crossing(rec, edges[1], k, width);
  return {std::min(a, b), std::max(a, b)};
}

ColumnRange strip_columns(const TriangleRecord& rec, int j, int width) {
  ColumnRange r = line_columns(rec, j, width);
  r.hull(line_columns(rec, j + 1, width));
  for (const VertexCells& v : rec.vertices)
    if (v.column != kNoCell && v.row == j) r.hull({v.column, v.column});
  if (r.empty()) return r;
  r.lo = std::max(r.lo, 0);
  r.hi = std::min(r.hi, width - 1);
  return r;
}

}  // namespace kinray
