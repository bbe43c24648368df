// Scheduling: the failure time of each certificate a record watches, and the event that fires at
// it. A vertex's certificates (its side of the eye plane and the two lines around each followed
// cell) share one event, an edge on a row line its two corners, a straddling triangle's
// orientation one; meshes have their keys and their presence.
#include <algorithm>
#include <limits>

#include "kinetic/core/certificate_time.h"
#include "kinetic/core/root_finding.h"
#include "kinetic/squares/pixel_square_sets.h"
#include "kinetic/squares/square_event_kinds.h"

namespace kinray {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

double PixelSquareSets::failure_time(int sign, const Polynomial& f, uint32_t mesh) const {
  const MeshSegment& seg = m_segments[mesh];
  // The zero polynomial reads as positive (sign_plus), as the records read it.
  if (f.is_zero()) return sign > 0 ? kInf : m_sim.now();
  if (f.degree == 1 &&
      linear_holds_through(sign > 0 ? f.c[0] : -f.c[0], sign > 0 ? f.c[1] : -f.c[1],
                           m_sim.now() - seg.origin, seg.end - seg.origin))
    return kInf;
  return certificate_failure_time(sign, f, seg.origin, m_sim.now(), seg.end);
}

void PixelSquareSets::schedule_all(uint32_t tri) {
  const TriangleRecord& rec = m_records[tri];
  if (rec.mode != TriangleRecord::Mode::kFront && rec.mode != TriangleRecord::Mode::kStraddling)
    return;
  // A record before the eye holds copies of its edges' steps, whose events are the edges'.
  if (rec.mode != TriangleRecord::Mode::kStraddling) return;
  const TriangleMotion tm = motion(tri);
  for (size_t e = 0; e < rec.lines.size(); ++e) schedule_line(tri, e, tm);
  schedule_orientation(tri, tm);
  for (int e = 0; e < 3; ++e) schedule_horizon(tri, e, tm);
}

void PixelSquareSets::schedule_vertex(uint32_t v) {
  VertexTracker& vt = m_vertices[v];
  const uint32_t m = m_vertex_mesh[v];
  if (m_input.meshes[m].is_static || !m_present[m] ||
      m_adjacency_begin[v] == m_adjacency_begin[v + 1]) {
    m_sim.queue().cancel(vt.event);
    return;
  }
  const PointMotion p = vertex_motion(v);
  const VertexCells& c = vt.cells;
  double t = failure_time(c.z_sign, Polynomial{p.a.z(), p.b.z()}, m);
  int count = 1;
  // The cell c claims "after line c" and "before line c + 1" (where those lines exist).
  auto watch = [&](int axis, int cell, int lines, const double* at) {
    if (cell == kNoCell) return;
    if (cell >= 0) t = std::min(t, failure_time(1, after_line(p, axis, at[cell], c.z_sign), m));
    if (cell + 1 < lines)
      t = std::min(t, failure_time(-1, after_line(p, axis, at[cell + 1], c.z_sign), m));
    count += 2;
  };
  watch(1, c.row, m_lattice.height() + 1, m_lattice.y_lines());
  watch(0, c.column, m_lattice.width() + 1, m_lattice.x_lines());
  m_stats.certificates_scheduled += uint64_t(count);
  m_sim.queue().schedule(vt.event, EventKey{t, kSquareVertex, v, 0}, v);
}

void PixelSquareSets::schedule_line(uint32_t tri, size_t entry, const TriangleMotion& tm) {
  EdgeOnLine& line = m_records[tri].lines[entry];
  const uint32_t m = m_triangle_mesh[tri];
  const EdgeNormal n = tm.edge(line.edge);
  const int w = m_lattice.width();
  const double y = m_lattice.y_line(line.line);
  const CornerStep& st = line.step;
  double t;
  if (st.count > w) {  // one sign all along: watch the two ends
    t = std::min(failure_time(st.first, n.along(m_lattice.x_line(0), y), m),
                 failure_time(st.first, n.along(m_lattice.x_line(w), y), m));
  } else {  // the two corners around the step
    t = std::min(failure_time(st.first, n.along(m_lattice.x_line(st.count - 1), y), m),
                 failure_time(-st.first, n.along(m_lattice.x_line(st.count), y), m));
  }
  m_stats.certificates_scheduled += 2;
  m_sim.queue().schedule(line.event, EventKey{t, kSquareCorner, tri, uint64_t(entry)},
                         square_event_payload(tri, entry));
}

void PixelSquareSets::schedule_edge_line(uint32_t edge, size_t index, const EdgeNormal& n) {
  EdgeStep& line = m_edges[edge].lines[index];
  const uint32_t m = m_vertex_mesh[m_edge_vertices[edge][0]];
  const int w = m_lattice.width();
  const double y = m_lattice.y_line(m_edges[edge].line_begin + int(index));
  const CornerStep& st = line.step;
  double t;
  if (st.count > w) {
    t = std::min(failure_time(st.first, n.along(m_lattice.x_line(0), y), m),
                 failure_time(st.first, n.along(m_lattice.x_line(w), y), m));
  } else {
    t = std::min(failure_time(st.first, n.along(m_lattice.x_line(st.count - 1), y), m),
                 failure_time(-st.first, n.along(m_lattice.x_line(st.count), y), m));
  }
  m_stats.certificates_scheduled += 2;
  m_sim.queue().schedule(line.event, EventKey{t, kSquareEdgeCorner, edge, uint64_t(index)},
                         square_event_payload(edge, index));
}

void PixelSquareSets::schedule_orientation(uint32_t tri, const TriangleMotion& tm) {
  TriangleRecord& rec = m_records[tri];
  const double t = failure_time(rec.orientation, tm.orientation(), m_triangle_mesh[tri]);
  ++m_stats.certificates_scheduled;
  m_sim.queue().schedule(rec.orientation_event, EventKey{t, kSquareOrientation, tri, 0},
                         square_event_payload(tri, 0));
}

void PixelSquareSets::schedule_horizon(uint32_t tri, int edge, const TriangleMotion& tm) {
  TriangleRecord& rec = m_records[tri];
  const double t =
      failure_time(rec.nx_sign[size_t(edge)], tm.edge(edge).component(0), m_triangle_mesh[tri]);
  ++m_stats.certificates_scheduled;
  m_sim.queue().schedule(rec.nx_events[size_t(edge)],
                         EventKey{t, kSquareHorizon, tri, uint64_t(edge)},
                         square_event_payload(tri, size_t(edge)));
}

void PixelSquareSets::schedule_key(uint32_t m) {
  const double t = m_input.meshes[m].is_static ? kInf : m_segments[m].end;
  m_sim.queue().schedule(m_key_events[m], EventKey{t, kSquareKey, m, 0}, m);
}

void PixelSquareSets::schedule_presence(uint32_t m) {
  const FlightplanMesh& mesh = m_input.meshes[m];
  const double now = m_sim.now();
  double t = kInf;
  if (m_present[m])
    t = mesh.disappear;
  else if (now < mesh.appear && mesh.appear < mesh.disappear)
    t = mesh.appear;
  m_sim.queue().schedule(m_presence_events[m], EventKey{t, kSquarePresence, m, 0}, m);
}

void PixelSquareSets::cancel_all(TriangleRecord& rec) {
  EventQueue& q = m_sim.queue();
  for (EdgeOnLine& line : rec.lines) q.cancel(line.event);
  q.cancel(rec.orientation_event);
  for (EventHandle& h : rec.nx_events) q.cancel(h);
}

}  // namespace kinray
