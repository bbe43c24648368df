// Meshes: insertion by scan conversion, removal, and the flightplan events that switch a mesh
// to its next segment and recompute its certificates.
#include "kinetic/grid/frustum_band.h"

#include <limits>
#include <vector>

namespace kinray {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

void FrustumBand::insert_mesh(uint32_t m, WorkProgress* progress) {
  const FlightplanMesh& mesh = m_scene.mesh(m);
  MeshState& ms = m_meshes[m];
  if (ms.present) return;
  ms.present = true;
  m_motion.set_segment(m, m_scene.segment_at(m, m_sim.now()));
  const uint32_t vb = m_scene.vertex_begin(m), ve = m_scene.vertex_end(m);
  std::vector<RowPattern> patterns(ve - vb);
  for (uint32_t v = vb; v < ve; ++v) {
    if (m_scene.triangles_of_vertex(v).empty()) continue;
    double s = 0;
    const PointMotion p = vertex_now(v, s);
    const RowPattern pattern = locate_vertex(p, s);
    patterns[v - vb] = pattern;
    if (!mesh.is_static) {
      SlotTracker& st = m_vertices[v];
      st.slot = pattern.slot;
      st.sign_lo = int8_t(pattern.sign_lo);
      st.sign_hi = int8_t(pattern.sign_hi);
      ++m_live_vertices;
      schedule_vertex(v);
    }
  }
  const int cull = m_scene.cull_sign(m);
  uint64_t unreported = 0;  // a shared counter touched once per 4096 triangles, not per triangle
  for (uint32_t tri = m_scene.triangle_begin(m); tri < m_scene.triangle_end(m); ++tri) {
    if (progress != nullptr && ++unreported == 4096) {
      progress->add(unreported);
      unreported = 0;
    }
    if (cull == 0) {
      scan_triangle(tri, patterns);
      continue;
    }
    // Culling: a triangle that meets the band's rows keeps its orientation, which turns its
    // records on and off; the others need none until a vertex-row event brings them in.
    const std::array<RowPattern, 3> p = mesh_patterns(tri, patterns);
    if (meets_rows(tri, p)) watch(tri, p);
  }
  if (progress != nullptr) progress->add(unreported);
  schedule_flightplan(m);
  double remove_at = kInf;
  if (mesh.disappear < kInf && mesh.disappear > m_sim.now()) remove_at = mesh.disappear;
  m_sim.queue().schedule(ms.remove, EventKey{remove_at, kGridRemove, m, 0}, m);
}

void FrustumBand::remove_mesh(uint32_t m) {
  const FlightplanMesh& mesh = m_scene.mesh(m);
  MeshState& ms = m_meshes[m];
  if (!ms.present) return;
  for (uint32_t tri = m_scene.triangle_begin(m); tri < m_scene.triangle_end(m); ++tri) {
    if (m_triangles[tri].watched) {
      unwatch(tri);
      continue;
    }
    while (m_triangles[tri].head != kNoRecord) kill_record(m_triangles[tri].head);
  }
  if (!mesh.is_static)
    for (uint32_t v = m_scene.vertex_begin(m); v < m_scene.vertex_end(m); ++v) {
      SlotTracker& st = m_vertices[v];
      if (m_scene.triangles_of_vertex(v).empty()) continue;
      m_sim.queue().cancel(st.event);
      st = SlotTracker{};
      --m_live_vertices;
    }
  for (EventHandle* h : {&ms.flightplan, &ms.remove})
    m_sim.queue().cancel(*h);
  ms.present = false;
}

void FrustumBand::handle_flightplans(uint32_t first_mesh) {
  // Every mesh reaching a key at this instant switches segment first, then their certificates
  // are recomputed together (one camera key moves every mesh at once).
  std::vector<uint32_t> meshes = {first_mesh};
  while (!m_sim.queue().empty() && m_sim.queue().top_key().time == m_sim.now() &&
         m_sim.queue().top_key().kind == kGridFlightplan) {
    meshes.push_back(uint32_t(m_sim.queue().top_payload()));
    m_sim.queue().pop();
  }
  for (uint32_t m : meshes) {
    m_meshes[m].flightplan = kNoEvent;
    m_motion.set_segment(m, m_scene.segment_at(m, m_sim.now()));
    schedule_flightplan(m);
    if (m_config.counts_meshes) ++m_stats.events.flightplan;
  }
  std::vector<uint8_t> switched(m_scene.mesh_count(), 0);
  for (uint32_t m : meshes) switched[m] = 1;
  for (uint32_t id = 0; id < m_boundaries.size(); ++id) {
    const EdgeBoundary& b = m_boundaries[id];
    if (b.unused() || !switched[m_scene.mesh_of_vertex(m_scene.edge_vertices(b.edge)[0])]) continue;
    schedule_boundary(id, edge_now(b.edge));
  }
  // The pixels holding a switched triangle, each once: a pixel's certificates between two
  // switched triangles are then computed once, not once per member.
  std::vector<size_t> pixels;
  for (uint32_t m : meshes) {
    if (!m_meshes[m].present) continue;
    const bool moving = !m_scene.mesh(m).is_static;
    if (moving)
      for (uint32_t v = m_scene.vertex_begin(m); v < m_scene.vertex_end(m); ++v)
        if (!m_scene.triangles_of_vertex(v).empty()) schedule_vertex(v);
    for (uint32_t tri = m_scene.triangle_begin(m); tri < m_scene.triangle_end(m); ++tri) {
      if (m_triangles[tri].head == kNoRecord && !m_triangles[tri].watched) continue;
      const TriangleNow tn = triangle_now(tri);
      schedule_orientation(tri, tn);
      for (uint32_t rec = m_triangles[tri].head; rec != kNoRecord; rec = m_records[rec].next) {
        const RowRecord& r = m_records[rec];
        for (int c = r.lo; c <= r.hi; ++c) {
          const size_t k = pixel_index(c, r.row);
          if (m_pixel_marks[k] != 0) continue;
          m_pixel_marks[k] = 1;
          pixels.push_back(k);
        }
      }
    }
  }
  for (const size_t k : pixels) {
    m_pixel_marks[k] = 0;
    refresh_front(k, m_orders->replace_motions(k, switched, m_sim.now()));
  }
}

}  // namespace kinray
