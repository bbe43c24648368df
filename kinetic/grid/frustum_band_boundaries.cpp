// Boundaries: the (edge, row) points shared by the records of an edge's two triangles, their
// slots among the columns, and the boundary events that move them across a column centre.
#include "kinetic/grid/frustum_band.h"

#include "util/check.h"

namespace kinray {

bool FrustumBand::bind_boundary(uint32_t rec, int k, const SlotTracker* hint) {
  const uint32_t edge = m_scene.edge_of_triangle(m_records[rec].triangle, m_records[rec].edge[size_t(k)]);
  const int row = m_records[rec].row;
  uint32_t id = m_edge_heads[edge];
  while (id != kNoBoundary && m_boundaries[id].row != row) id = m_boundaries[id].next;
  bool agrees = true;
  if (id == kNoBoundary) {
    if (!m_free_boundaries.empty()) {
      id = m_free_boundaries.back();
      m_free_boundaries.pop_back();
    } else {
      id = uint32_t(m_boundaries.size());
      m_boundaries.emplace_back();
    }
    EdgeBoundary& b = m_boundaries[id];
    b = EdgeBoundary{};
    b.edge = edge;
    b.row = row;
    b.next = m_edge_heads[edge];
    m_edge_heads[edge] = id;
    const EdgeNow en = edge_now(edge);
    if (hint == nullptr || !place_boundary(b, en, *hint)) {
      locate_boundary(b, en);
      agrees = hint == nullptr || b.tracker.slot == hint->slot;
    }
    if (en.moving) ++m_live_boundaries;
    schedule_boundary(id, en);
  } else if (hint != nullptr) {
    agrees = m_boundaries[id].tracker.slot == hint->slot;
  }
  EdgeBoundary& b = m_boundaries[id];
  KINRAY_CHECK_MSG(b.records[1] == kNoRecord, "an edge boundary bounds at most two records");
  (b.records[0] == kNoRecord ? b.records[0] : b.records[1]) = rec;
  m_records[rec].boundary[size_t(k)] = id;
  return agrees;
}

void FrustumBand::release_boundary(uint32_t rec, int k) {
  const uint32_t id = m_records[rec].boundary[size_t(k)];
  m_records[rec].boundary[size_t(k)] = kNoBoundary;
  EdgeBoundary& b = m_boundaries[id];
  if (b.records[0] == rec)
    b.records[0] = b.records[1];
  b.records[1] = kNoRecord;
  if (!b.unused()) return;
  m_sim.queue().cancel(b.tracker.event);
  if (m_edge_heads[b.edge] == id) {
    m_edge_heads[b.edge] = b.next;
  } else {
    uint32_t prev = m_edge_heads[b.edge];
    while (m_boundaries[prev].next != id) prev = m_boundaries[prev].next;
    m_boundaries[prev].next = b.next;
  }
  b.next = kNoBoundary;
  if (!m_scene.mesh(m_scene.mesh_of_vertex(m_scene.edge_vertices(b.edge)[0])).is_static)
    --m_live_boundaries;
  m_free_boundaries.push_back(id);
}

void FrustumBand::relocate_boundary(uint32_t id, uint32_t rec) {
  const EdgeNow en = edge_now(m_boundaries[id].edge);
  const SlotTracker before = m_boundaries[id].tracker;
  locate_boundary(m_boundaries[id], en);
  schedule_boundary(id, en);
  const SlotTracker& after = m_boundaries[id].tracker;
  if (after.slot == before.slot && after.sign_lo == before.sign_lo && after.sign_hi == before.sign_hi)
    return;
  // It moved without its event: the other record it bounds gets what that event would have done.
  const std::array<uint32_t, 2> records = m_boundaries[id].records;
  for (uint32_t other : records)
    if (other != kNoRecord && other != rec)
      rescan_record(other, triangle_now(m_records[other].triangle), true);
}

void FrustumBand::rebuild_boundary(uint32_t id) {
  ++m_stats.degenerate_rebuilds;
  const EdgeNow en = edge_now(m_boundaries[id].edge);
  locate_boundary(m_boundaries[id], en);
  schedule_boundary(id, en);
  const std::array<uint32_t, 2> records = m_boundaries[id].records;
  for (uint32_t rec : records)
    if (rec != kNoRecord) rescan_record(rec, triangle_now(m_records[rec].triangle), true);
}

void FrustumBand::handle_boundary(uint32_t id) {
  EdgeBoundary& b = m_boundaries[id];
  SlotTracker& st = b.tracker;
  st.event = kNoEvent;
  prefetch_other_normals(id);  // read by pass_column's coverage tests, after the schedule
  const EdgeNow en = edge_now(b.edge);
  const EdgeNormal& edge = m_motion.edge_normal(en.edge);
  const double y = m_scene.row_y(b.row);
  // The edge function along each column looked at, computed once: its sign here, then the
  // certificates of the new slot's columns and the coverage test of the column crossed.
  auto ray = [&](int c) { return EdgeOnRay(edge, m_scene.column_x(c), y, en.s); };
  if (st.slot == kBehindEye) {
    handle_boundary_behind_eye(id, en, edge);
    return;
  }
  // Plain ints, not a structured binding: clang 14 (the fuzz build) cannot capture one.
  const std::pair<int, int> watched = m_columns.watched(st.slot);
  const int lo = watched.first, hi = watched.second;
  const EdgeOnRay rl = ray(lo), rh = hi == lo ? rl : ray(hi);
  const int gl = rl.sign(edge, y, en.s), gh = hi == lo ? gl : rh.sign(edge, y, en.s);
  const bool changed_lo = gl != st.sign_lo, changed_hi = gh != st.sign_hi;
  if (st.slot == 0 && front_sign(en, b.row) < 0) {
    // Behind the eye through the eye plane, at infinity: nothing visible changes.
    ++m_stats.events.boundary;
    if (changed_lo || changed_hi) {
      rebuild_boundary(id);
      return;
    }
    st.slot = kBehindEye;
    st.sign_lo = st.sign_hi = 1;
    schedule_boundary(id, en, &edge);
    return;
  }
  std::array<EdgeOnRay, 2> rays = {rl, rh};  // the watched columns' (lo, hi), for the schedule
  if (!changed_lo && !changed_hi) {
    ++m_stats.spurious;
    schedule_boundary(id, en, &edge, &rays);
    return;
  }
  ++m_stats.events.boundary;
  int column = lo;
  if (lo == hi) {  // a one-column image: the only slot is off
    st.sign_lo = st.sign_hi = int8_t(gl);
  } else {
    if (changed_lo && changed_hi) {
      rebuild_boundary(id);
      return;
    }
    column = changed_lo ? lo : hi;
    const int slot = m_columns.across(st.slot, column);
    const auto [nlo, nhi] = m_columns.watched(slot);
    auto known = [&](int c) { return c == lo ? rl : (c == hi ? rh : ray(c)); };
    rays = {known(nlo), known(nhi)};
    auto known_sign = [&](int c, const EdgeOnRay& r) {
      return c == lo ? gl : (c == hi ? gh : r.sign(edge, y, en.s));
    };
    const int sl = known_sign(nlo, rays[0]), sh = known_sign(nhi, rays[1]);
    if (!SlotCircle::consistent(slot, sl, sh)) {
      rebuild_boundary(id);
      return;
    }
    st.slot = slot;
    st.sign_lo = int8_t(sl);
    st.sign_hi = int8_t(sh);
  }
  schedule_boundary(id, en, &edge, &rays);
  pass_column(id, column, en.s, column == lo ? rl : rh);
}

void FrustumBand::handle_boundary_behind_eye(uint32_t id, const EdgeNow& en,
                                             const EdgeNormal& edge) {
  SlotTracker& st = m_boundaries[id].tracker;
  const int row = m_boundaries[id].row;
  // Back in front through the eye plane, at infinity: the off slot. Nothing visible changes.
  if (front_sign(en, row) < 0) {
    ++m_stats.spurious;
    schedule_boundary(id, en, &edge);
    return;
  }
  ++m_stats.events.boundary;
  const double y = m_scene.row_y(row);
  auto sign_at = [&](int c) { return edge_sign(edge, m_scene.column_x(c), y, en.s); };
  const auto [lo, hi] = m_columns.watched(0);
  const int sl = sign_at(lo), sh = lo == hi ? sl : sign_at(hi);
  if (!SlotCircle::consistent(0, sl, sh)) {
    rebuild_boundary(id);
    return;
  }
  st.slot = 0;
  st.sign_lo = int8_t(sl);
  st.sign_hi = int8_t(sh);
  schedule_boundary(id, en, &edge);
}

void FrustumBand::pass_column(uint32_t id, int column, double s, const EdgeOnRay& own) {
  // The column passes from one triangle of the edge to the other: the one that loses it goes
  // first, so the pixel's order never holds both (no depth certificate between them).
  // Both triangles are on the edge's mesh segment, at its local time s, and both test the
  // boundary's own edge function at this column: `own`, the event's.
  const std::array<uint32_t, 2> records = m_boundaries[id].records;
  std::array<bool, 2> covered = {false, false};
  for (size_t k = 0; k < 2; ++k)
    if (records[k] != kNoRecord) covered[k] = covers_now(records[k], column, s, id, &own);
  // The usual crossing: one record loses the column at an end of its interval and the other
  // gains it at an end of its own. The pixel's order hands the one triangle's place to the other
  // in one change (the same order as erase then insert, without the two round trips).
  if (records[0] != kNoRecord && records[1] != kNoRecord && covered[0] != covered[1]) {
    const uint32_t loser = covered[0] ? records[1] : records[0];
    const uint32_t gainer = covered[0] ? records[0] : records[1];
    const RowRecord &l = m_records[loser], &g = m_records[gainer];
    int l_lo, l_hi, g_lo, g_hi;
    if (l.covers(column) && !g.covers(column) && interval_after(l, column, false, l_lo, l_hi) &&
        interval_after(g, column, true, g_lo, g_hi)) {
      const size_t k = pixel_index(column, l.row);
      m_stats.coverage_changes += 2;
      if (refresh_front(k, m_orders->hand_over(k, l.triangle, g.triangle, m_sim.now())))
        m_front_changed = true;
      if (m_config.audit) audit_pixel(column, l.row, m_sim.now());
      m_records[loser].lo = l_lo;
      m_records[loser].hi = l_hi;
      m_records[gainer].lo = g_lo;
      m_records[gainer].hi = g_hi;
      return;
    }
  }
  for (bool gains : {false, true})
    for (size_t k = 0; k < 2; ++k)
      if (records[k] != kNoRecord && covered[k] == gains) set_pixel(records[k], column, gains);
}

}  // namespace kinray
