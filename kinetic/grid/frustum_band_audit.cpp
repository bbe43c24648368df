// The band's brute-force audit (FrustumBand::audit): every invariant is checked by one member
// function of FrustumBand::Audit against the geometry recomputed from the scene at t, and every
// problem found names the band, the time, the invariant and where (mesh, vertex, triangle, row,
// edge or pixel). The pixel orders report their own problems (KineticSort::audit_problem), to
// which the band adds the pixel; nothing here aborts.
#include "kinetic/grid/frustum_band.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "kinetic/core/audit_failure.h"
#include "kinetic/grid/row_crossings.h"

namespace kinray {

class FrustumBand::Audit {
 public:
  Audit(const FrustumBand& band, double t, size_t limit)
      : m_band(band), m_t(t), m_limit(limit), m_expected(band.m_fronts.size(), 0) {}

  std::vector<std::string> run() && {
    queue_drained();
    for (uint32_t m = 0; m < m_band.m_scene.mesh_count(); ++m) mesh(m);
    boundaries();
    running_counts();
    pixels();
    return std::move(m_problems);
  }

 private:
  void report(const char* invariant, const std::string& where, const std::string& what) {
    if (m_problems.size() >= m_limit) return;
    char head[160];
    std::snprintf(head, sizeof head, "band rows [%d, %d) at t = %.17g: %s: ", m_band.m_row_begin,
                  m_band.m_row_end, m_t, invariant);
    m_problems.push_back(head + (where.empty() ? what : where + ": " + what));
  }
  static std::string triangle_row(uint32_t tri, int row) {
    return "triangle " + std::to_string(tri) + (row < 0 ? "" : " row " + std::to_string(row));
  }
  static std::string pixel(int column, int row) {
    return "pixel (" + std::to_string(column) + ", " + std::to_string(row) + ")";
  }

  /// Every event at or before t has been processed.
  void queue_drained() {
    const EventQueue& q = m_band.m_sim.queue();
    if (!q.empty() && q.top_key().time <= m_t)
      report("queue", "", "an event at or before the audit time is still pending");
  }

  /// A mesh is present exactly within its interval, on the flightplan segment of t; then its
  /// vertices and triangles.
  void mesh(uint32_t m) {
    const GridScene& scene = m_band.m_scene;
    const std::string where = "mesh " + std::to_string(m);
    if (m_band.m_meshes[m].present != scene.mesh(m).present(m_t))
      report("mesh presence", where, "presence differs from its interval");
    if (!m_band.m_meshes[m].present) return;
    if (scene.segment_at(m, m_t).index != m_band.m_motion.segment(m).index)
      report("mesh segment", where, "on the wrong flightplan segment");
    const std::vector<RowPattern> patterns = vertex_slots(m);
    for (uint32_t tri = scene.triangle_begin(m); tri < scene.triangle_end(m); ++tri)
      triangle(m, tri, patterns);
  }

  /// Each vertex of a moving mesh sits in the row slot of its point (signs at both watched rows);
  /// returns every vertex's pattern located afresh.
  std::vector<RowPattern> vertex_slots(uint32_t m) {
    const GridScene& scene = m_band.m_scene;
    const MeshSegment& current = m_band.m_motion.segment(m);
    const uint32_t vb = scene.vertex_begin(m), ve = scene.vertex_end(m);
    const double s = m_t - current.origin;
    std::vector<RowPattern> patterns(ve - vb);
    for (uint32_t v = vb; v < ve; ++v) {
      if (scene.triangles_of_vertex(v).empty()) continue;
      const PointMotion p = scene.vertex_motion(m, v - vb, current);
      patterns[v - vb] = m_band.locate_vertex(p, s);
      if (scene.mesh(m).is_static) continue;
      const SlotTracker& st = m_band.m_vertices[v];
      const auto [lo, hi] = m_band.m_rows.watched(st.slot);
      const int gl = sign_plus(row_side(p, scene.row_y(m_band.m_row_begin + lo)), s);
      const int gh = sign_plus(row_side(p, scene.row_y(m_band.m_row_begin + hi)), s);
      if (gl != st.sign_lo || gh != st.sign_hi || !SlotCircle::consistent(st.slot, gl, gh))
        report("vertex row slot", "vertex " + std::to_string(v), "wrong row slot");
    }
    return patterns;
  }

  /// The rows tri meets from its vertices' patterns: none if it is culled or degenerate.
  std::vector<int> rows_met(uint32_t tri, const std::vector<RowPattern>& patterns, uint32_t vb,
                            bool culled) const {
    std::vector<int> rows;
    const auto vs = m_band.m_scene.triangle_vertices(tri);
    if (culled || vs[0] == vs[1] || vs[1] == vs[2] || vs[2] == vs[0]) return rows;
    for (int q = 0; q < m_band.m_rows.count; ++q) {
      const int a = patterns[vs[0] - vb].sign(q), b = patterns[vs[1] - vb].sign(q),
                c = patterns[vs[2] - vb].sign(q);
      if (!(a == b && b == c)) rows.push_back(m_band.m_row_begin + q);
    }
    return rows;
  }

  /// A triangle has a record for exactly the rows it meets (none while culled), each record
  /// sound; with culling its orientation is kept exactly while it meets the band's rows; a kept
  /// orientation is the sign of O.
  void triangle(uint32_t m, uint32_t tri, const std::vector<RowPattern>& patterns) {
    const GridScene& scene = m_band.m_scene;
    const TriangleMotion motion = scene.triangle_motion(tri, m_band.m_motion.segment(m));
    const double s = m_t - m_band.m_motion.segment(m).origin;
    const CoverageRule rule(motion, s);
    const int cull = scene.cull_sign(m);
    const bool culled = cull != 0 && rule.orientation_sign() != cull;  // faces away: no records
    const std::vector<int> rows = rows_met(tri, patterns, scene.vertex_begin(m), culled);
    std::vector<int> held;
    const TriangleState& ts = m_band.m_triangles[tri];
    for (uint32_t rec = ts.head; rec != kNoRecord; rec = m_band.m_records[rec].next) {
      held.push_back(m_band.m_records[rec].row);
      record(tri, rec, motion, s, rule);
    }
    std::sort(held.begin(), held.end());
    const std::string where = triangle_row(tri, -1);
    if (held != rows) report("triangle rows", where, "records do not match the rows the triangle meets");
    const bool watched = cull != 0 && m_band.meets_rows(tri, m_band.mesh_patterns(tri, patterns));
    if (ts.watched != watched)
      report("culling watch", where,
             watched ? "meets the band's rows but its orientation is not kept"
                     : "orientation kept but the triangle meets no row");
    if ((!held.empty() || watched) && ts.orientation != rule.orientation_sign())
      report("orientation sign", where, "wrong orientation sign");
  }

  /// A record belongs to its triangle, its boundaries are tied to the two edges that cross its
  /// row and bound it, and it holds exactly the columns the triangle covers, each in that pixel's
  /// order.
  void record(uint32_t tri, uint32_t rec, const TriangleMotion& motion, double s,
              const CoverageRule& rule) {
    const FrustumBand& band = m_band;
    const RowRecord& r = band.m_records[rec];
    const std::string where = triangle_row(tri, r.row);
    if (r.triangle != tri) report("record list", where, "record of another triangle in the list");
    const double y = band.m_scene.row_y(r.row);
    std::array<int, 3> sides;
    for (int k = 0; k < 3; ++k) sides[size_t(k)] = sign_plus(row_side(motion.v[size_t(k)], y), s);
    int crossing[2];
    if (detail::crossing_edges(sides, crossing) == 2) {
      const bool ok = (r.edge[0] == crossing[0] && r.edge[1] == crossing[1]) ||
                      (r.edge[0] == crossing[1] && r.edge[1] == crossing[0]);
      if (!ok) report("record edges", where, "boundaries tied to the wrong edges");
    }
    for (int k = 0; k < 2; ++k) {
      const uint32_t id = r.boundary[size_t(k)];
      const bool bound = id < band.m_boundaries.size() &&
                         band.m_boundaries[id].edge == band.m_scene.edge_of_triangle(tri, r.edge[size_t(k)]) &&
                         band.m_boundaries[id].row == r.row &&
                         (band.m_boundaries[id].records[0] == rec || band.m_boundaries[id].records[1] == rec);
      if (!bound) report("record boundaries", where, "boundary " + std::to_string(k) + " not bound to its edge");
    }
    for (int c = 0; c < band.m_width; ++c) {
      const bool truth = rule.covers_in_row(band.m_scene.column_x(c), y, r.edge[0], r.edge[1]);
      const std::string column = where + " column " + std::to_string(c);
      if (truth != r.covers(c))
        report("record coverage", column, truth ? "covered but not held" : "held but not covered");
      if (!r.covers(c)) continue;
      ++m_expected[band.pixel_index(c, r.row)];
      if (!band.m_orders->contains(band.pixel_index(c, r.row), tri))
        report("record in pixel order", column, "missing from the pixel order");
    }
  }

  /// Every boundary in use is in its edge's list, bounds live records of its (edge, row), and sits
  /// in the slot of its point; every boundary is in use or free.
  void boundaries() {
    size_t in_use = 0;
    for (uint32_t id = 0; id < m_band.m_boundaries.size(); ++id) {
      if (m_band.m_boundaries[id].unused()) continue;
      ++in_use;
      boundary(id);
    }
    if (in_use + m_band.m_free_boundaries.size() != m_band.m_boundaries.size())
      report("boundary accounting", "", "boundaries neither in use nor free");
  }

  void boundary(uint32_t id) {
    const FrustumBand& band = m_band;
    const GridScene& scene = band.m_scene;
    const EdgeBoundary& b = band.m_boundaries[id];
    const std::string where = "edge " + std::to_string(b.edge) + " row " + std::to_string(b.row);
    uint32_t found = band.m_edge_heads[b.edge];
    while (found != kNoBoundary && found != id) found = band.m_boundaries[found].next;
    if (found != id) report("boundary list", where, "boundary missing from its edge's list");
    for (uint32_t rec : b.records)
      if (rec != kNoRecord &&
          (rec >= band.m_records.size() || band.m_records[rec].triangle == ~0u ||
           (band.m_records[rec].boundary[0] != id && band.m_records[rec].boundary[1] != id)))
        report("boundary records", where, "boundary names a record that does not hold it");
    const auto& ends = scene.edge_vertices(b.edge);
    const uint32_t m = scene.mesh_of_vertex(ends[0]);
    EdgeNow en;
    en.segment = band.m_motion.segment(m);
    const PointMotion p = scene.vertex_motion(m, ends[0] - scene.vertex_begin(m), en.segment);
    const PointMotion q = scene.vertex_motion(m, ends[1] - scene.vertex_begin(m), en.segment);
    en.p = &p;
    en.q = &q;
    en.s = m_t - en.segment.origin;
    const SlotTracker& st = b.tracker;
    const bool front = sign_plus(band.boundary_front(en, b.row), en.s) > 0;
    if (front == (st.slot == kBehindEye)) {
      report("boundary slot", where, front ? "in front but marked behind the eye" : "behind the eye but in a slot");
      return;
    }
    if (!front) return;
    const EdgeNormal edge = en.normal();
    const double y = scene.row_y(b.row);
    const auto [lo, hi] = band.m_columns.watched(st.slot);
    const int gl = edge_sign(edge, scene.column_x(lo), y, en.s);
    const int gh = edge_sign(edge, scene.column_x(hi), y, en.s);
    if (gl != st.sign_lo || gh != st.sign_hi || !SlotCircle::consistent(st.slot, gl, gh))
      report("boundary slot", where, "boundary in a wrong slot " + std::to_string(st.slot));
  }

  /// The running counts of pixel entries and pixel bytes (kept by every change of a pixel order,
  /// read by stats()) match the orders.
  void running_counts() {
    uint64_t entries = 0;
    size_t pixel_bytes = 0;
    m_band.m_orders->recount(entries, pixel_bytes);
    if (entries != m_band.m_orders->entries() || pixel_bytes != m_band.m_orders->memory_bytes())
      report("running counts", "", "the running count of pixel entries or pixel bytes is wrong");
  }

  /// Each pixel's order holds exactly the triangles whose records cover it, passes its own audit,
  /// and its front is the one in the band's front array.
  void pixels() {
    const FrustumBand& band = m_band;
    for (int j = band.m_row_begin; j < band.m_row_end; ++j)
      for (int i = 0; i < band.m_width; ++i) {
        const size_t k = band.pixel_index(i, j);
        if (band.m_orders->size(k) != m_expected[k])
          report("pixel set", pixel(i, j), "holds triangles that do not cover it");
        if (std::optional<std::string> problem = band.m_orders->audit_problem(k, m_t))
          report("pixel order", pixel(i, j), *problem);
        if (band.m_fronts[k] != band.m_orders->front(k))
          report("front array", pixel(i, j), "stale front in the band's front array");
      }
  }

  const FrustumBand& m_band;
  double m_t;
  size_t m_limit;
  std::vector<std::string> m_problems;
  std::vector<uint32_t> m_expected;  ///< per pixel: how many records cover it
};

std::vector<std::string> FrustumBand::audit(double t, size_t limit) const {
  return Audit(*this, t, limit).run();
}

void FrustumBand::audit_pixel(int column, int row, double t) const {
  std::optional<std::string> problem = m_orders->audit_problem(pixel_index(column, row), t);
  if (!problem) return;
  char head[160];
  std::snprintf(head, sizeof head, "kinetic audit: band rows [%d, %d) pixel (%d, %d) at t = %.17g: ",
                m_row_begin, m_row_end, column, row, t);
  throw KineticAuditFailure(head + *problem);
}

}  // namespace kinray
