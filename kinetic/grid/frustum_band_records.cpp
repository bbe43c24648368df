// Records: the (triangle, row) records, the interval of columns each covers, and the pixel
// orders that interval feeds (a change of coverage is an insert or an erase in a pixel order).
#include "kinetic/grid/frustum_band.h"

#include <algorithm>

#include "kinetic/grid/row_crossings.h"

namespace kinray {

using detail::crossing_edges;
using detail::sort_cuts;

template <class Covers>
std::pair<int, int> FrustumBand::scan_coverage(const RowRecord& r, int orientation, Covers&& covers,
                                               bool full) {
  if (orientation == 0) return {0, -1};
  const double y = m_scene.row_y(r.row);
  int lo = m_width, hi = -1, count = 0;
  if (!full) {
    // Coverage is constant between consecutive cuts: the boundary slots and the image borders
    // (the covered columns end only where the ray passes a boundary point in front of the eye).
    // A boundary behind the eye changes no coverage where it crosses (no cut).
    int cuts[4] = {0, std::max(m_boundaries[r.boundary[0]].tracker.slot, 0),
                   std::max(m_boundaries[r.boundary[1]].tracker.slot, 0), m_width};
    sort_cuts(cuts);
    for (int k = 0; k + 1 < 4; ++k) {
      const int a = cuts[k], b = cuts[k + 1];
      if (a >= b) continue;
      if (covers(m_scene.column_x(a), y)) {
        lo = std::min(lo, a);
        hi = std::max(hi, b - 1);
        count += b - a;
      }
    }
    if (count == hi - lo + 1 || count == 0) return count == 0 ? std::pair{0, -1} : std::pair{lo, hi};
    // Covered runs that are not contiguous: numerically degenerate; fall back to every column.
  }
  lo = m_width, hi = -1, count = 0;
  for (int c = 0; c < m_width; ++c)
    if (covers(m_scene.column_x(c), y)) {
      lo = std::min(lo, c);
      hi = c;
      ++count;
    }
  if (count == 0) return {0, -1};
  return {lo, hi};
}

void FrustumBand::pixel_insert(uint32_t tri, int column, int row) {
  const size_t k = pixel_index(column, row);
  ++m_stats.coverage_changes;
  if (refresh_front(k, m_orders->insert(k, tri, m_sim.now()))) m_front_changed = true;
  if (m_config.audit) audit_pixel(column, row, m_sim.now());
}

void FrustumBand::pixel_erase(uint32_t tri, int column, int row) {
  const size_t k = pixel_index(column, row);
  ++m_stats.coverage_changes;
  if (refresh_front(k, m_orders->erase(k, tri, m_sim.now()))) m_front_changed = true;
  if (m_config.audit) audit_pixel(column, row, m_sim.now());
}

uint32_t FrustumBand::find_record(uint32_t tri, int row) const {
  for (uint32_t rec = m_triangles[tri].head; rec != kNoRecord; rec = m_records[rec].next)
    if (m_records[rec].row == row) return rec;
  return kNoRecord;
}

void FrustumBand::set_coverage(uint32_t rec, int lo, int hi) {
  // Apply the difference between the old and the new interval to the pixel orders.
  const RowRecord old = m_records[rec];
  const bool empty = lo > hi;
  for (int c = old.lo; c <= old.hi; ++c)
    if (empty || c < lo || c > hi) pixel_erase(old.triangle, c, old.row);
  for (int c = lo; c <= hi; ++c)
    if (!old.covers(c)) pixel_insert(old.triangle, c, old.row);
  RowRecord& r = m_records[rec];
  r.lo = empty ? 0 : lo;
  r.hi = empty ? -1 : hi;
}

uint32_t FrustumBand::create_record(uint32_t tri, int row, int edge_a, int edge_b,
                                    const TriangleNow& tn) {
  uint32_t rec;
  if (!m_free_records.empty()) {
    rec = m_free_records.back();
    m_free_records.pop_back();
    m_records[rec] = RowRecord{};
  } else {
    rec = uint32_t(m_records.size());
    m_records.emplace_back();
  }
  TriangleState& ts = m_triangles[tri];
  // With culling the orientation is kept for every triangle, records or not.
  const bool first = ts.head == kNoRecord && m_scene.cull_sign_of_triangle(tri) == 0;
  RowRecord& r = m_records[rec];
  r.triangle = tri;
  r.row = row;
  r.next = ts.head;
  ts.head = rec;
  r.edge = {uint8_t(edge_a), uint8_t(edge_b)};
  bind_boundary(rec, 0);
  bind_boundary(rec, 1);
  ++m_stats.records_born;
  if (first) {
    ts.orientation = int8_t(sign_after(tn.motion.orientation(), tn.s));
    if (tn.moving) ++m_live_orientations;
    schedule_orientation(tri, tn);
  }
  // The sign rule of CoverageRule::covers_in_row from the band's cached edge normals, as
  // covers_now takes it: the same signs, without building the triangle's three normals.
  const int o = ts.orientation;
  auto covers = [&](double x, double y) {
    return cached_edge_sign(tri, edge_a, x, y, tn.s) == o &&
           cached_edge_sign(tri, edge_b, x, y, tn.s) == o;
  };
  const auto [lo, hi] = scan_coverage(m_records[rec], o, covers, false);
  set_coverage(rec, lo, hi);
  return rec;
}

void FrustumBand::kill_record(uint32_t rec) {
  set_coverage(rec, 0, -1);
  RowRecord& r = m_records[rec];
  const uint32_t tri = r.triangle;
  const bool moving = !m_scene.mesh(m_scene.mesh_of_triangle(tri)).is_static;
  release_boundary(rec, 0);
  release_boundary(rec, 1);
  TriangleState& ts = m_triangles[tri];
  if (ts.head == rec) {
    ts.head = r.next;
  } else {
    uint32_t prev = ts.head;
    while (m_records[prev].next != rec) prev = m_records[prev].next;
    m_records[prev].next = r.next;
  }
  if (ts.head == kNoRecord && m_scene.cull_sign_of_triangle(tri) == 0) {
    m_sim.queue().cancel(ts.event);
    ts.orientation = 0;
    if (moving) --m_live_orientations;
  }
  r.next = kNoRecord;
  r.triangle = ~0u;
  m_free_records.push_back(rec);
  ++m_stats.records_died;
}

void FrustumBand::rebuild_record(uint32_t rec, const TriangleNow& tn, bool full) {
  ++m_stats.row_rebuilds;
  int crossing[2];
  if (crossing_edges(row_sides(tn, m_records[rec].row), crossing) == 2) {
    // Keep a boundary whose edge still crosses; give the other the remaining crossing edge.
    const int e0 = m_records[rec].edge[0], e1 = m_records[rec].edge[1];
    auto crosses = [&](int e) { return e == crossing[0] || e == crossing[1]; };
    auto remaining = [&](int e) { return e == crossing[0] ? crossing[1] : crossing[0]; };
    std::array<int, 2> edges = {e0, e1};
    if (!(crosses(e0) && crosses(e1) && e0 != e1)) {
      if (crosses(e0))
        edges[1] = remaining(e0);
      else if (crosses(e1))
        edges[0] = remaining(e1);
      else
        edges = {crossing[0], crossing[1]};
    }
    for (int k = 0; k < 2; ++k) {
      if (edges[size_t(k)] == m_records[rec].edge[size_t(k)]) continue;
      release_boundary(rec, k);
      m_records[rec].edge[size_t(k)] = uint8_t(edges[size_t(k)]);
      bind_boundary(rec, k);
    }
  }
  // An event of a boundary at this very instant may still be pending (a rebuild at an
  // orientation event, when the plane sweeps through the eye and its boundaries with it): the
  // scan starts from their slots, so they are located afresh.
  for (int k = 0; k < 2; ++k) relocate_boundary(m_records[rec].boundary[size_t(k)], rec);
  rescan_record(rec, tn, full);
}

void FrustumBand::rescan_record(uint32_t rec, const TriangleNow& tn, bool full) {
  const CoverageRule rule(tn.motion, tn.s);
  const RowRecord& r = m_records[rec];
  const auto [lo, hi] = scan_coverage(
      r, rule.orientation_sign(),
      [&](double x, double y) { return rule.covers_in_row(x, y, r.edge[0], r.edge[1]); }, full);
  set_coverage(rec, lo, hi);
}

void FrustumBand::prefetch_coverage(const RowRecord& r) const {
  __builtin_prefetch(&m_triangles[r.triangle]);
  m_scene.prefetch_triangle(r.triangle);
}

void FrustumBand::prefetch_other_normals(uint32_t boundary) const {
  for (uint32_t rec : m_boundaries[boundary].records) {
    if (rec == kNoRecord) continue;
    const RowRecord& r = m_records[rec];
    const size_t other = r.boundary[0] == boundary ? 1 : 0;
    m_motion.prefetch_edge_normal(m_scene.edge_of_triangle(r.triangle, r.edge[other]));
  }
}

bool FrustumBand::covers_now(uint32_t rec, int column, double s, uint32_t boundary,
                             const EdgeOnRay* own) const {
  const RowRecord& r = m_records[rec];
  // The triangle's orientation sign is kept up to date by its orientation events (a change at
  // this very instant is still pending and rebuilds the record when processed). The edge
  // normals come from the cache: covers_in_row of the triangle's motion, bit for bit.
  const int o = m_triangles[r.triangle].orientation;
  if (o == 0) return false;
  const double x = m_scene.column_x(column), y = m_scene.row_y(r.row);
  // The given boundary's edge first: of the two records it bounds, the one that loses the column
  // is then answered without its other edge (the signs have no side effects, so the order does
  // not change the answer).
  const size_t first = own != nullptr && r.boundary[1] == boundary ? 1 : 0;
  for (const size_t k : {first, 1 - first}) {
    const int e = r.edge[k];
    int sign;
    if (own != nullptr && r.boundary[k] == boundary && own->v != 0) {
      // The given boundary's edge function along this column, already evaluated: a Horner
      // value that is not 0 is the sign, and the reversed normal's is its exact negation.
      sign = (own->v > 0) == (edge_direction(r.triangle, e) > 0) ? 1 : -1;
    } else {
      sign = cached_edge_sign(r.triangle, e, x, y, s);
    }
    if (sign != o) return false;
  }
  return true;
}

void FrustumBand::set_pixel(uint32_t rec, int column, bool covered) {
  const RowRecord& r = m_records[rec];
  if (covered == r.covers(column)) return;
  int lo, hi;
  if (!interval_after(r, column, covered, lo, hi)) {
    // Not at an end of the interval: several columns changed at one instant (degenerate).
    ++m_stats.degenerate_rebuilds;
    rebuild_record(rec, triangle_now(r.triangle), true);
    return;
  }
  // One column joins or leaves at an end: what set_coverage(rec, lo, hi) would do, without its
  // walk over the old and the new interval.
  const uint32_t tri = r.triangle;
  const int row = r.row;
  if (covered)
    pixel_insert(tri, column, row);
  else
    pixel_erase(tri, column, row);
  m_records[rec].lo = lo;
  m_records[rec].hi = hi;
}

void FrustumBand::update_triangle_row(uint32_t tri, int row) {
  if (culled(tri)) return;  // no records while it faces away
  const TriangleNow tn = triangle_now(tri);
  int crossing[2];
  const int n = crossing_edges(row_sides(tn, row), crossing);
  const uint32_t rec = find_record(tri, row);
  if (n == 0) {
    if (rec != kNoRecord) kill_record(rec);
    return;
  }
  if (rec == kNoRecord) {
    create_record(tri, row, crossing[0], crossing[1], tn);
    return;
  }
  RowRecord& r = m_records[rec];
  const int e0 = r.edge[0], e1 = r.edge[1];
  const bool has0 = e0 == crossing[0] || e0 == crossing[1];
  const bool has1 = e1 == crossing[0] || e1 == crossing[1];
  if (has0 && has1 && e0 != e1) return;  // this vertex was not an end of a crossing edge here
  ++m_stats.reties;
  if (has0 == has1) {  // both edges changed at once (degenerate)
    ++m_stats.degenerate_rebuilds;
    rebuild_record(rec, tn, true);
    return;
  }
  // The boundary on the edge that stopped crossing moves on to the new edge through the vertex:
  // the point is continuous, so its slot stays (the new edge's boundary may already be held by
  // the triangle across that edge); only its certificates change.
  const int bi = has0 ? 1 : 0;
  const int other = r.edge[size_t(1 - bi)];
  const SlotTracker old = m_boundaries[r.boundary[size_t(bi)]].tracker;
  release_boundary(rec, bi);
  m_records[rec].edge[size_t(bi)] = uint8_t(crossing[0] == other ? crossing[1] : crossing[0]);
  if (!bind_boundary(rec, bi, &old)) {
    ++m_stats.degenerate_rebuilds;
    rescan_record(rec, tn, true);
    return;
  }
  const int slot = m_boundaries[m_records[rec].boundary[size_t(bi)]].tracker.slot;
  if (slot == kBehindEye) return;
  // At the instant of the re-tie the boundary is the vertex itself; a vertex exactly on a
  // pixel-centre ray may change that pixel, so the two watched columns are re-evaluated.
  const auto [lo, hi] = m_columns.watched(slot);
  update_pixel(rec, lo, tn);
  if (hi != lo) update_pixel(rec, hi, tn);
}

}  // namespace kinray
