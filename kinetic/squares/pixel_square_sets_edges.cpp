// Edges: the corner steps of an edge between two vertices before the eye are followed once for
// the (usually two) triangles on either side of it (edge_steps.h), and a corner event moves the
// step in both of their records.
#include <algorithm>
#include <unordered_map>

#include "kinetic/grid/mesh_segments.h"
#include "kinetic/squares/pixel_square_sets.h"
#include "kinetic/squares/square_event_kinds.h"
#include "util/check.h"

namespace kinray {

void PixelSquareSets::index_edges() {
  std::unordered_map<uint64_t, uint32_t> ids;
  m_triangle_edges.resize(m_records.size());
  for (uint32_t tri = 0; tri < m_records.size(); ++tri) {
    const std::array<uint32_t, 3> vs = vertex_ids(tri);
    for (int e = 0; e < 3; ++e) {
      const uint32_t a = vs[size_t(kEdgeStart[e])], b = vs[size_t(kEdgeEnd[e])];
      const uint32_t lo = std::min(a, b), hi = std::max(a, b);
      const auto [it, inserted] =
          ids.try_emplace((uint64_t(lo) << 32) | hi, uint32_t(m_edge_vertices.size()));
      if (inserted) m_edge_vertices.push_back({lo, hi});
      m_triangle_edges[tri][size_t(e)] = it->second;
    }
  }
  const size_t edges = m_edge_vertices.size();
  m_edges.resize(edges);
  m_edge_triangles_begin.assign(edges + 1, 0);
  for (const auto& es : m_triangle_edges)
    for (uint32_t id : es) ++m_edge_triangles_begin[id + 1];
  for (size_t k = 0; k < edges; ++k) m_edge_triangles_begin[k + 1] += m_edge_triangles_begin[k];
  m_edge_triangles.resize(m_edge_triangles_begin.back());
  std::vector<uint32_t> fill(m_edge_triangles_begin.begin(), m_edge_triangles_begin.end() - 1);
  for (uint32_t tri = 0; tri < m_records.size(); ++tri)
    for (uint32_t id : m_triangle_edges[tri]) m_edge_triangles[fill[id]++] = tri;
}

int PixelSquareSets::edge_direction(uint32_t tri, int e) const {
  const std::array<uint32_t, 3> vs = vertex_ids(tri);
  return vs[size_t(kEdgeStart[e])] <= vs[size_t(kEdgeEnd[e])] ? 1 : -1;
}

EdgeNormal PixelSquareSets::edge_normal_of(uint32_t edge) const {
  // edge_normal is exactly antisymmetric: a triangle running the edge the other way has exactly
  // the negated function, so the copies' negated signs are its own.
  const auto& ends = m_edge_vertices[edge];
  return edge_normal(vertex_motion(ends[0]), vertex_motion(ends[1]));
}

void PixelSquareSets::layout_edge(uint32_t edge) {
  EdgeTracker& et = m_edges[edge];
  const auto& ends = m_edge_vertices[edge];
  const int r0 = m_vertices[ends[0]].cells.row, r1 = m_vertices[ends[1]].cells.row;
  KINRAY_CHECK(r0 != kNoCell && r1 != kNoCell);
  // The row lines strictly between the end points' rows (clamped to the image).
  const int begin = std::max(std::min(r0, r1) + 1, 0);
  const int end = std::max(std::min(std::max(r0, r1), m_lattice.height()) + 1, begin);
  std::vector<EdgeStep> old = std::move(et.lines);
  const int old_begin = et.line_begin;
  et.line_begin = begin;
  et.lines.assign(size_t(end - begin), EdgeStep{});
  const EdgeNormal n = edge_normal_of(edge);
  const double s = vertex_local_time(ends[0]);
  const bool moving = !m_input.meshes[m_vertex_mesh[ends[0]]].is_static;
  for (int k = begin; k < end; ++k) {
    EdgeStep& line = et.lines[size_t(k - begin)];
    if (k >= old_begin && k < old_begin + int(old.size())) {  // kept: its step and event go on
      line = old[size_t(k - old_begin)];
      old[size_t(k - old_begin)].event = kNoEvent;
      if (line.event != kNoEvent)
        m_sim.queue().set_payload(line.event, square_event_payload(edge, size_t(k - begin)));
      continue;
    }
    line.step =
        locate_corner_step(n, m_lattice.width() + 1, m_lattice.x_lines(), m_lattice.y_line(k), s);
    if (moving) schedule_edge_line(edge, size_t(k - begin), n);
  }
  for (EdgeStep& line : old) m_sim.queue().cancel(line.event);
}

void PixelSquareSets::follow_edge(uint32_t edge) {
  if (m_edges[edge].users++ == 0) layout_edge(edge);
}

void PixelSquareSets::unfollow_edge(uint32_t edge) {
  EdgeTracker& et = m_edges[edge];
  KINRAY_CHECK(et.users > 0);
  if (--et.users != 0) return;
  for (EdgeStep& line : et.lines) m_sim.queue().cancel(line.event);
  et.lines.clear();
}

std::vector<uint32_t> PixelSquareSets::followed_edges_at(uint32_t v) const {
  std::vector<uint32_t> edges;
  for (uint32_t k = m_adjacency_begin[v]; k < m_adjacency_begin[v + 1]; ++k)
    for (uint32_t id : m_triangle_edges[m_adjacency[k]])
      if (m_edges[id].users > 0 && (m_edge_vertices[id][0] == v || m_edge_vertices[id][1] == v) &&
          std::find(edges.begin(), edges.end(), id) == edges.end())
        edges.push_back(id);
  return edges;
}

void PixelSquareSets::schedule_edge(uint32_t edge) {
  if (m_edges[edge].users == 0) return;
  const EdgeNormal n = edge_normal_of(edge);
  for (size_t k = 0; k < m_edges[edge].lines.size(); ++k) schedule_edge_line(edge, k, n);
}

void PixelSquareSets::edge_corner_event(uint32_t edge, size_t index) {
  EdgeTracker& et = m_edges[edge];
  EdgeStep& line = et.lines[index];
  line.event = kNoEvent;
  const int k = et.line_begin + int(index);
  const EdgeNormal n = edge_normal_of(edge);
  const CornerStep step =
      walk_corner_step(line.step, n, m_lattice.width() + 1, m_lattice.x_lines(),
                       m_lattice.y_line(k), vertex_local_time(m_edge_vertices[edge][0]));
  if (step.first != line.step.first || step.count != line.step.count) {
    ++m_stats.events.corner;
    line.step = step;
    for (uint32_t a = m_edge_triangles_begin[edge]; a < m_edge_triangles_begin[edge + 1]; ++a) {
      const uint32_t tri = m_edge_triangles[a];
      TriangleRecord& rec = m_records[tri];
      if (rec.mode != TriangleRecord::Mode::kFront) continue;
      for (int e = 0; e < 3; ++e) {
        if (m_triangle_edges[tri][size_t(e)] != edge) continue;
        const int dir = edge_direction(tri, e);
        KINRAY_DCHECK(k >= rec.line_begin && k < rec.line_end());
        for (int b = 0; b < 2; ++b) {
          EdgeOnLine& copy = rec.lines[size_t((k - rec.line_begin) * 2 + b)];
          if (copy.edge == e) copy.step = CornerStep{dir * step.first, step.count};
        }
      }
      // Row line k bounds strips k - 1 (above) and k (below).
      refresh_strips(tri, k - 1, k + 1);
    }
  } else {
    ++m_stats.spurious;
  }
  schedule_edge_line(edge, index, n);
}

}  // namespace kinray
