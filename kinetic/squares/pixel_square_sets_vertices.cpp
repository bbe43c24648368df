// Vertices: each is followed once, whatever the number of triangles around it. A vertex that
// changes side of the eye plane rebuilds every triangle around it (their modes may change), one
// that changes row reshapes the records that read its cells (which lines and edges they follow
// changes near the line it crossed), and one that crosses a column line within its row moves that
// cell in their records and recomputes the strip it lies in.
#include "kinetic/grid/mesh_segments.h"
#include "kinetic/squares/pixel_square_sets.h"
#include "util/check.h"

namespace kinray {

namespace {

/// z(s) of a vertex: its side of the eye plane, read by sign_plus like every other certificate (a
/// vertex held in the eye plane all segment long counts as before it, with its projection at
/// infinity), so that its claim and its failure time agree and it cannot fire at once for ever.
int z_sign_of(const PointMotion& p, double s) {
  return sign_plus(Polynomial{p.a.z(), p.b.z()}, s);
}

bool reads_cells(TriangleRecord::Mode mode) {
  return mode == TriangleRecord::Mode::kFront || mode == TriangleRecord::Mode::kStraddling;
}

}  // namespace

PointMotion PixelSquareSets::vertex_motion(uint32_t v) const {
  const uint32_t m = m_vertex_mesh[v];
  return mesh_vertex_motion(m_input.meshes[m], v - m_vertex_begin[m], m_segments[m]);
}

void PixelSquareSets::locate_vertex(uint32_t v) {
  VertexCells& c = m_vertices[v].cells;
  const PointMotion p = vertex_motion(v);
  const double s = vertex_local_time(v);
  c.z_sign = int8_t(z_sign_of(p, s));
  c.row = c.column = kNoCell;
  if (m_vertices[v].users == 0) return;
  c.row = int16_t(locate_cell(p, 1, c.z_sign, m_lattice.height() + 1, m_lattice.y_lines(), s));
  if (c.z_sign > 0)  // behind the eye a vertex is no vertex of R: only its row is read
    c.column = int16_t(locate_cell(p, 0, c.z_sign, m_lattice.width() + 1, m_lattice.x_lines(), s));
}

void PixelSquareSets::follow(uint32_t v) {
  if (m_vertices[v].users++ != 0) return;
  locate_vertex(v);
  schedule_vertex(v);
}

void PixelSquareSets::unfollow(uint32_t v) {
  KINRAY_CHECK(m_vertices[v].users > 0);
  if (--m_vertices[v].users != 0) return;
  m_vertices[v].cells.row = m_vertices[v].cells.column = kNoCell;
  schedule_vertex(v);
}

void PixelSquareSets::vertex_event(uint32_t v) {
  VertexTracker& vt = m_vertices[v];
  vt.event = kNoEvent;
  const PointMotion p = vertex_motion(v);
  const double s = vertex_local_time(v);
  const VertexCells was = vt.cells;
  if (z_sign_of(p, s) != was.z_sign) {
    locate_vertex(v);
  } else if (vt.users > 0) {
    VertexCells& c = vt.cells;
    c.row =
        int16_t(walk_cell(c.row, p, 1, c.z_sign, m_lattice.height() + 1, m_lattice.y_lines(), s));
    if (c.column != kNoCell)
      c.column = int16_t(
          walk_cell(c.column, p, 0, c.z_sign, m_lattice.width() + 1, m_lattice.x_lines(), s));
  }
  const VertexCells is = vt.cells;
  const auto around =
      std::span(m_adjacency)
          .subspan(m_adjacency_begin[v], m_adjacency_begin[v + 1] - m_adjacency_begin[v]);
  if (is.z_sign != was.z_sign) {
    ++m_stats.events.rebuild;
    for (uint32_t tri : around) rebuild(tri);
  } else if (is.row != was.row) {
    ++m_stats.events.row;
    // The edges first: the records copy their steps.
    for (uint32_t edge : followed_edges_at(v)) layout_edge(edge);
    for (uint32_t tri : around)
      if (reads_cells(m_records[tri].mode)) reshape(tri);
  } else if (is.column != was.column) {
    ++m_stats.events.side;
    for (uint32_t tri : around) {
      TriangleRecord& rec = m_records[tri];
      if (!reads_cells(rec.mode)) continue;
      const std::array<uint32_t, 3> ids = vertex_ids(tri);
      for (int k = 0; k < 3; ++k)
        if (ids[size_t(k)] == v) rec.vertices[size_t(k)].column = is.column;
      refresh_strips(tri, is.row, is.row + 1);
    }
  } else {
    ++m_stats.spurious;
  }
  schedule_vertex(v);
}

}  // namespace kinray
