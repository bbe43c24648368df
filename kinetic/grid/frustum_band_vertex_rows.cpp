// Vertex rows: each vertex's slot among the band's row planes, the rows a triangle meets from
// its vertices' slots, and the vertex-row events that change them.
#include "kinetic/grid/frustum_band.h"

#include <algorithm>
#include <optional>

#include "kinetic/grid/row_crossings.h"

namespace kinray {

using detail::crossing_edges;
using detail::sort_cuts;

void FrustumBand::handle_vertex(uint32_t v) {
  SlotTracker& st = m_vertices[v];
  st.event = kNoEvent;
  double s = 0;
  const PointMotion p = vertex_now(v, s);
  auto sign_at = [&](int q) { return row_side_sign(p, m_scene.row_y(m_row_begin + q), s); };
  // Plain ints, not a structured binding: clang 14 (the fuzz build) cannot capture one.
  const std::pair<int, int> watched = m_rows.watched(st.slot);
  const int lo = watched.first, hi = watched.second;
  const int gl = sign_at(lo), gh = hi == lo ? gl : sign_at(hi);
  const bool changed_lo = gl != st.sign_lo, changed_hi = gh != st.sign_hi;
  if (!changed_lo && !changed_hi) {
    ++m_stats.spurious;
    schedule_vertex(v);
    return;
  }
  const RowPattern before{st.slot, st.sign_lo, st.sign_hi};
  RowPattern after;
  bool simple = false;
  if (lo == hi) {
    after = RowPattern{0, gl, gl};
    simple = true;
  } else if (changed_lo != changed_hi) {
    const int row = changed_lo ? lo : hi;
    const int slot = m_rows.across(st.slot, row);
    const auto [nlo, nhi] = m_rows.watched(slot);
    auto known = [&](int q) { return q == lo ? gl : (q == hi ? gh : sign_at(q)); };
    after = RowPattern{slot, known(nlo), known(nhi)};
    simple = SlotCircle::consistent(slot, after.sign_lo, after.sign_hi);
  }
  if (!simple) after = locate_vertex(p, s);  // several row planes at one instant (degenerate)
  st.slot = after.slot;
  st.sign_lo = int8_t(after.sign_lo);
  st.sign_hi = int8_t(after.sign_hi);
  schedule_vertex(v);
  if (m_scene.cull_sign(m_scene.mesh_of_vertex(v)) != 0) {
    // Culling: a triangle that starts meeting the band's rows starts being watched, with its
    // records for every row it meets; one that stops meeting them stops (update_triangle_row
    // skips both, and the triangles that are not watched).
    for (uint32_t tri : m_scene.triangles_of_vertex(v)) {
      const std::array<RowPattern, 3> patterns = tracked_patterns(tri);
      const bool meets = meets_rows(tri, patterns);
      if (meets == m_triangles[tri].watched) continue;
      if (meets)
        watch(tri, patterns);
      else
        unwatch(tri);
      m_watch_changed.push_back(tri);
    }
  }
  // A simple crossing changes the side of row lo or hi only: visiting just those two (in
  // ascending order, as the full scan would) spares a loop over every row of the band per event.
  const std::array<int, 2> simple_rows = {std::min(lo, hi), std::max(lo, hi)};
  const int rows_to_visit = simple ? (lo == hi ? 1 : 2) : m_rows.count;
  for (int k = 0; k < rows_to_visit; ++k) {
    const int q = simple ? simple_rows[size_t(k)] : k;
    if (before.sign(q) == after.sign(q)) continue;
    ++m_stats.events.vertex_row;
    for (uint32_t tri : m_scene.triangles_of_vertex(v))
      if (std::find(m_watch_changed.begin(), m_watch_changed.end(), tri) == m_watch_changed.end())
        update_triangle_row(tri, m_row_begin + q);
  }
  m_watch_changed.clear();
}

void FrustumBand::scan_triangle(uint32_t tri, const std::vector<RowPattern>& patterns) {
  const auto vs = m_scene.triangle_vertices(tri);
  if (vs[0] == vs[1] || vs[1] == vs[2] || vs[2] == vs[0]) return;  // never covers anything
  scan_rows(tri, mesh_patterns(tri, patterns));
}

std::array<FrustumBand::RowPattern, 3> FrustumBand::mesh_patterns(
    uint32_t tri, const std::vector<RowPattern>& patterns) const {
  const auto& vs = m_scene.triangle_vertices(tri);
  const uint32_t base = m_scene.vertex_begin(m_scene.mesh_of_triangle(tri));
  return {patterns[vs[0] - base], patterns[vs[1] - base], patterns[vs[2] - base]};
}

bool FrustumBand::meets_rows(uint32_t tri, const std::array<RowPattern, 3>& p) const {
  const auto& vs = m_scene.triangle_vertices(tri);
  if (vs[0] == vs[1] || vs[1] == vs[2] || vs[2] == vs[0]) return false;
  // Some row has vertices on both sides iff the three patterns differ as functions of the rows
  // (without sorting the slots into runs and testing each).
  auto key = [&](const RowPattern& v) {
    return detail::row_step(v.slot, v.sign_lo, v.sign_hi, m_rows.count);
  };
  const detail::RowStep k0 = key(p[0]);
  return !(key(p[1]) == k0 && key(p[2]) == k0);
}

std::array<FrustumBand::RowPattern, 3> FrustumBand::tracked_patterns(uint32_t tri) const {
  const auto& vs = m_scene.triangle_vertices(tri);
  std::array<RowPattern, 3> p;
  for (int k = 0; k < 3; ++k) {
    const SlotTracker& st = m_vertices[vs[size_t(k)]];
    p[size_t(k)] = RowPattern{st.slot, st.sign_lo, st.sign_hi};
  }
  return p;
}

void FrustumBand::scan_rows(uint32_t tri, const std::array<RowPattern, 3>& p) {
  int cuts[5] = {0, p[0].slot, p[1].slot, p[2].slot, m_rows.count};
  sort_cuts(cuts);
  std::optional<TriangleNow> tn;
  for (int k = 0; k + 1 < 5; ++k) {
    const int a = cuts[k], b = cuts[k + 1];
    if (a >= b) continue;
    const std::array<int, 3> sides = {p[0].sign(a), p[1].sign(a), p[2].sign(a)};
    int crossing[2];
    if (crossing_edges(sides, crossing) != 2) continue;
    if (!tn) tn = triangle_now(tri);
    for (int q = a; q < b; ++q) create_record(tri, m_row_begin + q, crossing[0], crossing[1], *tn);
  }
}

}  // namespace kinray
