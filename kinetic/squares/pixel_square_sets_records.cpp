// Records: a triangle's record built from the signs at now() (start-up, rebuilds), its strips'
// columns, and the pixels it is added to or removed from when they change.
#include <algorithm>

#include "kinetic/grid/mesh_segments.h"
#include "kinetic/squares/pixel_square_sets.h"
#include "kinetic/squares/square_event_kinds.h"
#include "util/check.h"

namespace kinray {

namespace {

using Mode = TriangleRecord::Mode;

}  // namespace

std::array<uint32_t, 3> PixelSquareSets::vertex_ids(uint32_t tri) const {
  const uint32_t m = m_triangle_mesh[tri];
  const auto& local = m_input.meshes[m].triangles[tri - m_triangle_begin[m]];
  return {m_vertex_begin[m] + local[0], m_vertex_begin[m] + local[1], m_vertex_begin[m] + local[2]};
}

TriangleMotion PixelSquareSets::motion(uint32_t tri) const {
  const uint32_t m = m_triangle_mesh[tri];
  const FlightplanMesh& mesh = m_input.meshes[m];
  const auto& local = mesh.triangles[tri - m_triangle_begin[m]];
  TriangleMotion tm;
  for (int k = 0; k < 3; ++k)
    tm.v[size_t(k)] = mesh_vertex_motion(mesh, local[size_t(k)], m_segments[m]);
  return tm;
}

void PixelSquareSets::follow_lines(uint32_t tri, TriangleRecord& rec, const TriangleMotion& tm,
                                   double s, TriangleRecord* old) const {
  const int w = m_lattice.width(), h = m_lattice.height();
  std::array<EdgeNormal, 3> normals;
  for (int e = 0; e < 3; ++e) normals[size_t(e)] = tm.edge(e);
  int line_end = 0;
  if (rec.mode == Mode::kFront) {
    // Only the row lines strictly between the vertices' rows meet R, each crossed by two edges.
    int rmin = h, rmax = -1;
    for (const VertexCells& vc : rec.vertices) {
      rmin = std::min<int>(rmin, vc.row);
      rmax = std::max<int>(rmax, vc.row);
    }
    rec.edges_per_line = 2;
    rec.line_begin = std::max(rmin + 1, 0);
    line_end = std::max(std::min(rmax, h) + 1, rec.line_begin);
    rec.strip_begin = std::max(rmin, 0);
    rec.strips.resize(size_t(std::max(std::min(rmax, h - 1) + 1 - rec.strip_begin, 0)));
  } else {
    rec.edges_per_line = 3;
    rec.line_begin = 0;
    line_end = h + 1;
    rec.strip_begin = 0;
    rec.strips.resize(size_t(h));
  }
  for (int k = rec.line_begin; k < line_end; ++k)
    for (int e = 0; e < 3; ++e) {
      if (rec.mode == Mode::kFront) {
        const bool start_below = rec.vertices[size_t(kEdgeStart[e])].row >= k;
        const bool end_below = rec.vertices[size_t(kEdgeEnd[e])].row >= k;
        if (start_below == end_below) continue;
      }
      EdgeOnLine line;
      line.line = int16_t(k);
      line.edge = int8_t(e);
      if (rec.mode == Mode::kFront) {  // a copy of the edge's own step (followed already)
        const EdgeTracker& et = m_edges[m_triangle_edges[tri][size_t(e)]];
        KINRAY_DCHECK(k >= et.line_begin && k - et.line_begin < int(et.lines.size()));
        const CornerStep& own = et.lines[size_t(k - et.line_begin)].step;
        line.step = CornerStep{edge_direction(tri, e) * own.first, own.count};
        rec.lines.push_back(line);
        continue;
      }
      EdgeOnLine* kept = nullptr;
      if (old != nullptr && k >= old->line_begin && k < old->line_end())
        for (int a = 0; a < old->edges_per_line; ++a) {
          EdgeOnLine& candidate =
              old->lines[size_t((k - old->line_begin) * old->edges_per_line + a)];
          if (candidate.edge == e) kept = &candidate;
        }
      if (kept != nullptr) {  // the same edge on the same line: its step and its event go on
        line.step = kept->step;
        line.event = kept->event;
        kept->event = kNoEvent;
      } else {
        line.step = locate_corner_step(normals[size_t(e)], w + 1, m_lattice.x_lines(),
                                       m_lattice.y_line(k), s);
      }
      rec.lines.push_back(line);
    }
  KINRAY_CHECK_EQ(rec.lines.size(), size_t((line_end - rec.line_begin) * rec.edges_per_line));
}

void PixelSquareSets::compute_strips(TriangleRecord& rec) const {
  for (size_t k = 0; k < rec.strips.size(); ++k)
    rec.strips[k] = strip_columns(rec, rec.strip_begin + int(k), m_lattice.width());
}

TriangleRecord::Mode PixelSquareSets::mode_of(uint32_t tri, const TriangleMotion& tm) const {
  if (!m_present[m_triangle_mesh[tri]]) return Mode::kAbsent;
  // Degenerate all segment long: R is empty until the next key.
  if (tm.orientation().is_zero()) return Mode::kEmpty;
  int front = 0;
  for (uint32_t v : vertex_ids(tri)) front += m_vertices[v].cells.z_sign > 0;
  // No forward ray meets a triangle wholly behind the eye.
  return front == 0 ? Mode::kBehind : (front == 3 ? Mode::kFront : Mode::kStraddling);
}

void PixelSquareSets::build(uint32_t tri, TriangleRecord& rec) const {
  rec = TriangleRecord{};
  const TriangleMotion tm = motion(tri);
  rec.mode = mode_of(tri, tm);
  if (rec.mode != Mode::kFront && rec.mode != Mode::kStraddling) return;
  const double s = local_time(tri);
  rec.orientation = int8_t(sign_after(tm.orientation(), s));
  if (rec.mode == Mode::kStraddling)
    for (int e = 0; e < 3; ++e)
      rec.nx_sign[size_t(e)] = int8_t(sign_plus(tm.edge(e).component(0), s));
  const std::array<uint32_t, 3> ids = vertex_ids(tri);
  for (int k = 0; k < 3; ++k) rec.vertices[size_t(k)] = m_vertices[ids[size_t(k)]].cells;
  follow_lines(tri, rec, tm, s);
  compute_strips(rec);
}

namespace {
/// Whether a record of this mode reads its vertices' cells.
bool reads_cells(TriangleRecord::Mode mode) {
  return mode == TriangleRecord::Mode::kFront || mode == TriangleRecord::Mode::kStraddling;
}
}  // namespace

void PixelSquareSets::rebuild(uint32_t tri) {
  TriangleRecord before = std::move(m_records[tri]);
  cancel_all(before);
  const std::array<uint32_t, 3> ids = vertex_ids(tri);
  // The new record's vertices are followed before the old record lets them go, so that a vertex
  // both read is not dropped and located again.
  const Mode mode = mode_of(tri, motion(tri));
  if (reads_cells(mode))
    for (uint32_t v : ids) follow(v);
  if (mode == Mode::kFront)
    for (uint32_t edge : m_triangle_edges[tri]) follow_edge(edge);
  build(tri, m_records[tri]);
  if (before.mode == Mode::kFront)
    for (uint32_t edge : m_triangle_edges[tri]) unfollow_edge(edge);
  if (reads_cells(before.mode))
    for (uint32_t v : ids) unfollow(v);
  ++m_stats.records_built;
  const TriangleRecord& rec = m_records[tri];
  const int j0 = std::min(before.strip_begin, rec.strip_begin);
  const int j1 = std::max(before.strip_begin + int(before.strips.size()),
                          rec.strip_begin + int(rec.strips.size()));
  update_pixels(tri, before, j0, j1);
  if (moving(tri)) schedule_all(tri);
}

void PixelSquareSets::reshape(uint32_t tri) {
  TriangleRecord& rec = m_records[tri];
  // The old layout: its strips tell which pixels change. A straddling triangle follows every row
  // line with all three edges whatever its vertices' rows, so its lines are all taken over with
  // their steps and events; one before the eye copies its lines from its edges, laid out again
  // already (layout_edge).
  TriangleRecord before;
  before.strip_begin = rec.strip_begin;
  before.strips = std::move(rec.strips);
  before.line_begin = rec.line_begin;
  before.edges_per_line = rec.edges_per_line;
  before.lines = std::move(rec.lines);
  rec.strips.clear();
  rec.lines.clear();
  const std::array<uint32_t, 3> ids = vertex_ids(tri);
  for (int k = 0; k < 3; ++k) rec.vertices[size_t(k)] = m_vertices[ids[size_t(k)]].cells;
  const TriangleMotion tm = motion(tri);
  follow_lines(tri, rec, tm, local_time(tri), &before);
  compute_strips(rec);
  for (EdgeOnLine& line : before.lines) m_sim.queue().cancel(line.event);
  ++m_stats.records_reshaped;
  const int j0 = std::min(before.strip_begin, rec.strip_begin);
  const int j1 = std::max(before.strip_begin + int(before.strips.size()),
                          rec.strip_begin + int(rec.strips.size()));
  update_pixels(tri, before, j0, j1);
  if (rec.mode != Mode::kStraddling) return;  // a front record's lines are copies, eventless
  for (size_t e = 0; e < rec.lines.size(); ++e) {
    if (rec.lines[e].event != kNoEvent)  // a kept event, now at this index
      m_sim.queue().set_payload(rec.lines[e].event, square_event_payload(tri, e));
    else
      schedule_line(tri, e, tm);
  }
}

void PixelSquareSets::clear(uint32_t tri) {
  TriangleRecord before = std::move(m_records[tri]);
  cancel_all(before);
  m_records[tri] = TriangleRecord{};
  if (before.mode == Mode::kFront)
    for (uint32_t edge : m_triangle_edges[tri]) unfollow_edge(edge);
  if (reads_cells(before.mode))
    for (uint32_t v : vertex_ids(tri)) unfollow(v);
  update_pixels(tri, before, before.strip_begin, before.strip_begin + int(before.strips.size()));
}

void PixelSquareSets::update_pixels(uint32_t tri, const TriangleRecord& before, int j0, int j1) {
  const TriangleRecord& rec = m_records[tri];
  for (int j = j0; j < j1; ++j) {
    const ColumnRange was = before.strip(j), is = rec.strip(j);
    for (int i = was.lo; i <= was.hi; ++i)
      if (!is.contains(i)) remove(tri, i, j);
    for (int i = is.lo; i <= is.hi; ++i)
      if (!was.contains(i)) add(tri, i, j);
  }
}

void PixelSquareSets::refresh_strips(uint32_t tri, int j0, int j1) {
  TriangleRecord& rec = m_records[tri];
  j0 = std::max(j0, rec.strip_begin);
  j1 = std::min(j1, rec.strip_begin + int(rec.strips.size()));
  for (int j = j0; j < j1; ++j) {
    ColumnRange& held = rec.strips[size_t(j - rec.strip_begin)];
    const ColumnRange was = held, is = strip_columns(rec, j, m_lattice.width());
    held = is;
    for (int i = was.lo; i <= was.hi; ++i)
      if (!is.contains(i)) remove(tri, i, j);
    for (int i = is.lo; i <= is.hi; ++i)
      if (!was.contains(i)) add(tri, i, j);
  }
}

void PixelSquareSets::add(uint32_t tri, int i, int j) {
  const uint32_t m = m_triangle_mesh[tri];
  const size_t pixel = size_t(j) * size_t(m_lattice.width()) + size_t(i);
  const SquareTriangle entry{m, tri - m_triangle_begin[m]};
  m_pixels[pixel].push_back(entry);
  ++m_stats.square_changes;
  if (m_logging) m_changes.push_back({m_sim.now(), uint32_t(pixel), entry, true});
}

void PixelSquareSets::remove(uint32_t tri, int i, int j) {
  const uint32_t m = m_triangle_mesh[tri];
  const size_t pixel = size_t(j) * size_t(m_lattice.width()) + size_t(i);
  const SquareTriangle entry{m, tri - m_triangle_begin[m]};
  std::vector<SquareTriangle>& set = m_pixels[pixel];
  const auto it = std::find(set.begin(), set.end(), entry);
  KINRAY_CHECK_MSG(it != set.end(), "a triangle left a square it was not in");
  *it = set.back();
  set.pop_back();
  ++m_stats.square_changes;
  if (m_logging) m_changes.push_back({m_sim.now(), uint32_t(pixel), entry, false});
}

}  // namespace kinray
