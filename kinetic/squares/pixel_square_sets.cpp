// PixelSquareSets: start-up, the event loop, and the events of meshes (keys, presence) and of
// triangles (a straddling triangle's plane sweeping the eye or one of its edges turning
// horizontal rebuilds its record; an edge line passing a corner moves one step and recomputes the
// two strips its row line bounds). The vertices' and the edges' events are in
// pixel_square_sets_vertices.cpp and pixel_square_sets_edges.cpp.
#include "kinetic/squares/pixel_square_sets.h"

#include <string>

#include "kinetic/core/audit_failure.h"
#include "kinetic/grid/mesh_segments.h"
#include "kinetic/squares/square_event_kinds.h"
#include "util/check.h"

namespace kinray {

PixelSquareSets::PixelSquareSets(GridInput input, double start_time, const Config& config)
    : m_input(std::move(input)), m_lattice(m_input.rays), m_config(config), m_sim(start_time) {
  KINRAY_CHECK(m_lattice.width() > 0 && m_lattice.height() > 0);
  const size_t meshes = m_input.meshes.size();
  m_triangle_begin.push_back(0);
  m_vertex_begin.push_back(0);
  for (uint32_t m = 0; m < meshes; ++m) {
    const FlightplanMesh& mesh = m_input.meshes[m];
    validate_mesh(mesh, "mesh " + std::to_string(m) + ": ");
    m_triangle_begin.push_back(m_triangle_begin.back() + uint32_t(mesh.triangles.size()));
    m_triangle_mesh.resize(m_triangle_begin.back(), m);
    m_vertex_begin.push_back(m_vertex_begin.back() + uint32_t(mesh.vertex_count));
    m_vertex_mesh.resize(m_vertex_begin.back(), m);
    m_segments.push_back(mesh_segment_at(mesh, start_time));
    m_present.push_back(mesh.present(start_time) ? 1 : 0);
  }
  m_key_events.assign(meshes, kNoEvent);
  m_presence_events.assign(meshes, kNoEvent);
  m_records.resize(m_triangle_begin.back());
  m_pixels.resize(m_lattice.rays().pixel_count());
  // Each vertex's triangles (a vertex repeated in a degenerate triangle is listed twice).
  const uint32_t vertex_count = m_vertex_begin.back();
  m_vertices.resize(vertex_count);
  m_adjacency_begin.assign(size_t(vertex_count) + 1, 0);
  for (uint32_t tri = 0; tri < m_records.size(); ++tri)
    for (uint32_t v : vertex_ids(tri)) ++m_adjacency_begin[v + 1];
  for (uint32_t v = 0; v < vertex_count; ++v) m_adjacency_begin[v + 1] += m_adjacency_begin[v];
  m_adjacency.resize(m_adjacency_begin.back());
  std::vector<uint32_t> fill(m_adjacency_begin.begin(), m_adjacency_begin.end() - 1);
  for (uint32_t tri = 0; tri < m_records.size(); ++tri)
    for (uint32_t v : vertex_ids(tri)) m_adjacency[fill[v]++] = tri;
  index_edges();
  // Start-up: every present vertex's side of the eye, then every present triangle's record from
  // the signs at the start time (rebuild follows its vertices' cells and adds it to the squares
  // its strips hold).
  for (uint32_t v = 0; v < vertex_count; ++v)
    if (m_present[m_vertex_mesh[v]]) locate_vertex(v);
  for (uint32_t tri = 0; tri < m_records.size(); ++tri)
    if (m_present[m_triangle_mesh[tri]]) rebuild(tri);
  for (uint32_t v = 0; v < vertex_count; ++v) schedule_vertex(v);
  for (uint32_t m = 0; m < meshes; ++m) {
    schedule_key(m);
    schedule_presence(m);
  }
}

void PixelSquareSets::advance_to(double t) {
  m_sim.advance_to(t, [this](const EventKey& key, uint64_t payload) { handle(key, payload); });
  if (!m_config.audit) return;
  const std::vector<std::string> problems = audit();
  if (!problems.empty())
    throw KineticAuditFailure("per-square sets: " + problems.front() + " (" +
                              std::to_string(problems.size()) + " problems)");
}

void PixelSquareSets::handle(const EventKey& key, uint64_t payload) {
  const uint32_t tri = uint32_t(payload >> 32);
  const size_t sub = size_t(payload & 0xffffffffu);
  switch (key.kind) {
    case kSquareKey: {
      const uint32_t m = key.a;
      m_key_events[m] = kNoEvent;
      ++m_stats.events.flightplan;
      m_segments[m] = mesh_segment_at(m_input.meshes[m], m_sim.now());
      // The vertices are continuous across a key, and so is every record: only its certificates
      // are recomputed on the new segment. One that the key's rounding leaves failing fires now
      // and is handled like any other event. A triangle degenerate on either segment (O the zero
      // polynomial, whose record is empty) is rebuilt.
      for (uint32_t v = m_vertex_begin[m]; v < m_vertex_begin[m + 1]; ++v) schedule_vertex(v);
      for (uint32_t t = m_triangle_begin[m]; t < m_triangle_begin[m + 1]; ++t)
        for (uint32_t edge : m_triangle_edges[t])
          if (m_edge_triangles[m_edge_triangles_begin[edge]] == t) schedule_edge(edge);  // once
      if (m_present[m])
        for (uint32_t t = m_triangle_begin[m]; t < m_triangle_begin[m + 1]; ++t) {
          if (m_records[t].mode == TriangleRecord::Mode::kEmpty ||
              motion(t).orientation().is_zero())
            rebuild(t);
          else
            schedule_all(t);
        }
      schedule_key(m);
      break;
    }
    case kSquarePresence: {
      const uint32_t m = key.a;
      m_presence_events[m] = kNoEvent;
      const bool present = m_input.meshes[m].present(m_sim.now());
      if (present != bool(m_present[m])) {
        m_present[m] = present ? 1 : 0;
        if (present) {
          ++m_stats.events.insert;
          m_segments[m] = mesh_segment_at(m_input.meshes[m], m_sim.now());
          for (uint32_t v = m_vertex_begin[m]; v < m_vertex_begin[m + 1]; ++v) locate_vertex(v);
          for (uint32_t t = m_triangle_begin[m]; t < m_triangle_begin[m + 1]; ++t) rebuild(t);
        } else {
          ++m_stats.events.remove;
          for (uint32_t t = m_triangle_begin[m]; t < m_triangle_begin[m + 1]; ++t) clear(t);
        }
        for (uint32_t v = m_vertex_begin[m]; v < m_vertex_begin[m + 1]; ++v) schedule_vertex(v);
      }
      schedule_presence(m);
      break;
    }
    case kSquareOrientation:
      m_records[tri].orientation_event = kNoEvent;
      ++m_stats.events.rebuild;
      rebuild(tri);
      break;
    case kSquareHorizon:
      // An edge line turned horizontal: its crossings of the row lines went through infinity.
      m_records[tri].nx_events[sub] = kNoEvent;
      ++m_stats.events.rebuild;
      rebuild(tri);
      break;
    case kSquareVertex:
      vertex_event(key.a);
      break;
    case kSquareCorner:
      corner_event(tri, sub);
      break;
    case kSquareEdgeCorner:
      edge_corner_event(key.a, sub);
      break;
    default:
      KINRAY_CHECK_MSG(false, "unknown event kind");
  }
}

void PixelSquareSets::corner_event(uint32_t tri, size_t entry) {
  TriangleRecord& rec = m_records[tri];
  EdgeOnLine& line = rec.lines[entry];
  line.event = kNoEvent;
  const TriangleMotion tm = motion(tri);
  const CornerStep step =
      walk_corner_step(line.step, tm.edge(line.edge), m_lattice.width() + 1, m_lattice.x_lines(),
                       m_lattice.y_line(line.line), local_time(tri));
  if (step.first != line.step.first || step.count != line.step.count) {
    ++m_stats.events.corner;
    line.step = step;
    // Row line k bounds strips k - 1 (above) and k (below).
    refresh_strips(tri, line.line - 1, line.line + 1);
  } else {
    ++m_stats.spurious;
  }
  schedule_line(tri, entry, tm);
}

SquareStats PixelSquareSets::stats() const {
  SquareStats s = m_stats;
  for (const auto& set : m_pixels) s.pixel_entries += set.size();
  s.events_pending = m_sim.queue().size();
  for (const VertexTracker& v : m_vertices) s.vertices_followed += v.users > 0;
  for (const EdgeTracker& e : m_edges) s.edges_followed += e.users > 0;
  for (const TriangleRecord& rec : m_records) {
    s.triangles_front += rec.mode == TriangleRecord::Mode::kFront;
    s.triangles_straddling += rec.mode == TriangleRecord::Mode::kStraddling;
  }
  return s;
}

std::array<Eigen::Vector3d, 3> PixelSquareSets::triangle_at(uint32_t m, uint32_t triangle,
                                                            double t) const {
  const FlightplanMesh& mesh = m_input.meshes[m];
  const FlightplanMesh::KeyBlend blend = mesh.blend_at(t);
  const auto& vs = mesh.triangles[triangle];
  return {mesh.position(vs[0], blend), mesh.position(vs[1], blend), mesh.position(vs[2], blend)};
}

}  // namespace kinray
