#include "kinetic/frustum_band.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "kinetic/certificate_time.h"
#include "kinetic/check.h"
#include "kinetic/kinetic_heap.h"
#include "kinetic/kinetic_sorted_list.h"
#include "kinetic/kinetic_tournament.h"
#include "kinetic/root_finding.h"

namespace kinray {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The edges whose end points lie on different sides: none or two of them.
int crossing_edges(const std::array<int, 3>& sides, int out[2]) {
  int n = 0;
  for (int e = 0; e < 3; ++e)
    if (sides[kEdgeStart[e]] != sides[kEdgeEnd[e]]) {
      if (n < 2) out[n] = e;
      ++n;
    }
  return n;
}

// Sorts the 4 or 5 cuts of a row or a band in place: an insertion sort, inline (std::sort's
// call and introsort set-up cost more than the sort itself here; the result is the same).
template <size_t N>
void sort_cuts(int (&cuts)[N]) {
  for (size_t i = 1; i < N; ++i) {
    const int v = cuts[i];
    size_t j = i;
    for (; j > 0 && cuts[j - 1] > v; --j) cuts[j] = cuts[j - 1];
    cuts[j] = v;
  }
}

}  // namespace

template <class Sort>
FrustumBand<Sort>::FrustumBand(const GridScene& scene, int row_begin, int row_end,
                               const Config& config)
    : m_scene(scene),
      m_config(config),
      m_row_begin(row_begin),
      m_row_end(row_end),
      m_width(scene.width()),
      m_columns{scene.width()},
      m_rows{row_end - row_begin},
      m_motion(scene) {
  KINRAY_CHECK(row_begin >= 0 && row_begin < row_end && row_end <= scene.height());
  m_meshes.resize(scene.mesh_count());
  m_triangles.resize(scene.triangle_count());
  m_vertices.resize(scene.vertex_count());
  m_edge_heads.assign(scene.edge_count(), kNoBoundary);
  KineticSortConfig sort_config;
  sort_config.event_kind = kGridSwap;
  sort_config.audit = false;  // the band audits at consistent points (not mid flightplan batch)
  sort_config.shared_stats = &m_sort_stats;
  const size_t pixels = size_t(row_end - row_begin) * size_t(m_width);
  m_pixels.reserve(pixels);
  for (int j = row_begin; j < row_end; ++j)
    for (int i = 0; i < m_width; ++i)
      m_pixels.emplace_back(&m_motion, i, j, m_queue,
                            uint32_t(size_t(j) * size_t(m_width) + size_t(i)), sort_config);
  m_fronts.assign(pixels, kNoFront);
  for (const PixelCell& p : m_pixels) m_pixel_bytes += p.order.memory_bytes() + sizeof(PixelDepthKeys);
}

// ---------------------------------------------------------------------------------------------
// Geometry just after now.

template <class Sort>
typename FrustumBand<Sort>::TriangleNow FrustumBand<Sort>::triangle_now(uint32_t tri) const {
  TriangleNow tn;
  const uint32_t m = m_scene.mesh_of_triangle(tri);
  tn.segment = m_motion.segment(m);
  tn.motion = m_motion.triangle(tri);
  tn.s = m_now - tn.segment.origin;
  tn.moving = !m_scene.mesh(m).is_static;
  return tn;
}

template <class Sort>
typename FrustumBand<Sort>::EdgeNow FrustumBand<Sort>::edge_now(uint32_t edge) const {
  EdgeNow en;
  const auto& ends = m_scene.edge_vertices(edge);
  const uint32_t m = m_scene.mesh_of_vertex(ends[0]);
  en.segment = m_motion.segment(m);
  en.p = m_motion.vertex(ends[0]);
  en.q = m_motion.vertex(ends[1]);
  en.s = m_now - en.segment.origin;
  en.moving = !m_scene.mesh(m).is_static;
  en.edge = edge;
  return en;
}

template <class Sort>
PointMotion FrustumBand<Sort>::vertex_now(uint32_t v, double& s) const {
  s = m_now - m_motion.segment(m_scene.mesh_of_vertex(v)).origin;
  return m_motion.vertex(v);
}

template <class Sort>
typename FrustumBand<Sort>::RowPattern FrustumBand<Sort>::locate_vertex(const PointMotion& p,
                                                                        double s) const {
  auto sign_at = [&](int q) { return sign_plus(row_side(p, m_scene.row_y(m_row_begin + q)), s); };
  RowPattern pattern;
  pattern.slot = m_rows.locate(sign_at);
  const auto [lo, hi] = m_rows.watched(pattern.slot);
  pattern.sign_lo = sign_at(lo);
  pattern.sign_hi = lo == hi ? pattern.sign_lo : sign_at(hi);
  if (!SlotCircle::consistent(pattern.slot, pattern.sign_lo, pattern.sign_hi))
    pattern.sign_hi = pattern.slot == 0 ? pattern.sign_lo : -pattern.sign_lo;
  return pattern;
}

template <class Sort>
Polynomial FrustumBand<Sort>::boundary_front(const EdgeNow& en, int row) const {
  const double y = m_scene.row_y(row);
  const Polynomial z = boundary_depth(en.p, en.q, y);
  return sign_plus(row_side(en.q, y), en.s) > 0 ? z : -z;
}

template <class Sort>
void FrustumBand<Sort>::locate_boundary(EdgeBoundary& b, const EdgeNow& en) const {
  SlotTracker& t = b.tracker;
  if (sign_plus(boundary_front(en, b.row), en.s) < 0) {
    t.slot = kBehindEye;
    t.sign_lo = t.sign_hi = 1;
    return;
  }
  const EdgeNormal& edge = m_motion.edge_normal(en.edge);
  const double y = m_scene.row_y(b.row);
  auto sign_at = [&](int c) { return edge_sign(edge, m_scene.column_x(c), y, en.s); };
  t.slot = m_columns.locate(sign_at);
  const auto [lo, hi] = m_columns.watched(t.slot);
  t.sign_lo = int8_t(sign_at(lo));
  t.sign_hi = int8_t(lo == hi ? t.sign_lo : sign_at(hi));
  // A sign pattern that is not monotone (rounding of a nearly constant edge function) still
  // gets a consistent slot; the audit reports such rows if they ever matter.
  if (!SlotCircle::consistent(t.slot, t.sign_lo, t.sign_hi))
    t.sign_hi = int8_t(t.slot == 0 ? t.sign_lo : -t.sign_lo);
}

template <class Sort>
bool FrustumBand<Sort>::place_boundary(EdgeBoundary& b, const EdgeNow& en,
                                       const SlotTracker& hint) const {
  // The new edge's point is the same point: on the same side of the eye, in the same slot.
  SlotTracker& t = b.tracker;
  const bool front = sign_plus(boundary_front(en, b.row), en.s) > 0;
  if (hint.slot == kBehindEye) {
    if (front) return false;
    t.slot = kBehindEye;
    t.sign_lo = t.sign_hi = 1;
    return true;
  }
  if (!front) return false;
  const EdgeNormal& edge = m_motion.edge_normal(en.edge);
  const double y = m_scene.row_y(b.row);
  const auto [lo, hi] = m_columns.watched(hint.slot);
  const int sl = edge_sign(edge, m_scene.column_x(lo), y, en.s);
  const int sh = lo == hi ? sl : edge_sign(edge, m_scene.column_x(hi), y, en.s);
  if (!SlotCircle::consistent(hint.slot, sl, sh)) return false;
  t.slot = hint.slot;
  t.sign_lo = int8_t(sl);
  t.sign_hi = int8_t(sh);
  return true;
}

template <class Sort>
std::array<int, 3> FrustumBand<Sort>::row_sides(const TriangleNow& tn, int row) const {
  const double y = m_scene.row_y(row);
  return {sign_plus(row_side(tn.motion.v[0], y), tn.s), sign_plus(row_side(tn.motion.v[1], y), tn.s),
          sign_plus(row_side(tn.motion.v[2], y), tn.s)};
}

template <class Sort>
std::pair<int, int> FrustumBand<Sort>::scan_coverage(const RowRecord& r, const CoverageRule& rule,
                                                     bool full) {
  if (rule.orientation_sign() == 0) return {0, -1};
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
      if (rule.covers_in_row(m_scene.column_x(a), y, r.edge[0], r.edge[1])) {
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
    if (rule.covers_in_row(m_scene.column_x(c), y, r.edge[0], r.edge[1])) {
      lo = std::min(lo, c);
      hi = c;
      ++count;
    }
  if (count == 0) return {0, -1};
  return {lo, hi};
}

// ---------------------------------------------------------------------------------------------
// Scheduling.

template <class Sort>
double FrustumBand<Sort>::failure_time(int sign, const Polynomial& f, const MeshSegment& seg) const {
  if (sign == 0) return f.is_zero() ? kInf : m_now;
  // The zero polynomial reads as positive (sign_plus). An edge function that vanishes identically
  // is watched through its perturbed sign (EdgeNormal::perturbed), which can still change within
  // the segment: n_x changes sign where n is normal to d and to x, i.e. to the row plane (the edge
  // lies in it, or its line passes through the eye), and n_y, when n_x vanishes too, where n = 0.
  // Those are scheduled like any other crossing, so the slots never hold a stale perturbed sign.
  if (f.is_zero()) return sign > 0 ? kInf : m_now;
  // A vertex's row side: most vertices lie outside a band's rows all segment long, and each band
  // watches every vertex at every key, so first_failure's quick answer is taken without the call.
  if (f.degree == 1 && linear_holds_through(sign > 0 ? f.c[0] : -f.c[0], sign > 0 ? f.c[1] : -f.c[1],
                                            m_now - seg.origin, seg.end - seg.origin))
    return kInf;
  return certificate_failure_time(sign > 0 ? f : -f, seg.origin, m_now, seg.end);
}

template <class Sort>
void FrustumBand<Sort>::set_event(EventHandle& handle, double time, const EventKey& key,
                                  uint64_t payload) {
  if (time == kInf) {
    if (handle != kNoEvent) m_queue.erase(handle);
    handle = kNoEvent;
    return;
  }
  EventKey k = key;
  k.time = time;
  if (handle == kNoEvent) {
    handle = m_queue.push(k, payload);
  } else {
    m_queue.update(handle, k);
    m_queue.set_payload(handle, payload);
  }
}

template <class Sort>
void FrustumBand<Sort>::schedule_boundary(uint32_t id, const EdgeNow& en, const EdgeNormal* known) {
  if (!en.moving) return;
  EdgeBoundary& b = m_boundaries[id];
  SlotTracker& st = b.tracker;
  double t;
  if (st.slot == kBehindEye) {
    t = failure_time(-1, boundary_front(en, b.row), en.segment);
  } else {
    const EdgeNormal& edge = known ? *known : m_motion.edge_normal(en.edge);
    const double y = m_scene.row_y(b.row);
    const auto [lo, hi] = m_columns.watched(st.slot);
    t = failure_time(st.sign_lo, edge.perturbed(m_scene.column_x(lo), y), en.segment);
    if (hi != lo) t = std::min(t, failure_time(st.sign_hi, edge.perturbed(m_scene.column_x(hi), y), en.segment));
    // Only from the off slot (at infinity) can the point pass behind the eye.
    if (st.slot == 0) t = std::min(t, failure_time(1, boundary_front(en, b.row), en.segment));
  }
  m_stats.certificates_computed += 2;
  set_event(st.event, t, EventKey{0, kGridBoundary, uint32_t(b.row), b.edge}, id);
}

template <class Sort>
void FrustumBand<Sort>::schedule_vertex(uint32_t v) {
  SlotTracker& st = m_vertices[v];
  double s = 0;
  const PointMotion p = vertex_now(v, s);
  const MeshSegment& seg = m_motion.segment(m_scene.mesh_of_vertex(v));
  const auto [lo, hi] = m_rows.watched(st.slot);
  double t = failure_time(st.sign_lo, row_side(p, m_scene.row_y(m_row_begin + lo)), seg);
  if (hi != lo) t = std::min(t, failure_time(st.sign_hi, row_side(p, m_scene.row_y(m_row_begin + hi)), seg));
  m_stats.certificates_computed += 2;
  set_event(st.event, t, EventKey{0, kGridVertexRow, v, 0}, v);
}

template <class Sort>
void FrustumBand<Sort>::schedule_orientation(uint32_t tri, const TriangleNow& tn) {
  if (!tn.moving) return;
  TriangleState& ts = m_triangles[tri];
  // O is the zero polynomial on a segment where the triangle is degenerate throughout (a sliver
  // whose vertices are collinear over this key interval but not the last): its sign is then 0,
  // not the + that failure_time reads the zero polynomial as, so a kept sign changes now.
  const Polynomial o = tn.motion.orientation();
  const double t = o.is_zero() ? (ts.orientation == 0 ? kInf : m_now)
                               : failure_time(ts.orientation, o, tn.segment);
  ++m_stats.certificates_computed;
  set_event(ts.event, t, EventKey{0, kGridOrientation, tri, 0}, tri);
}

template <class Sort>
void FrustumBand<Sort>::schedule_flightplan(uint32_t m) {
  const GridMesh& mesh = m_scene.mesh(m);
  MeshState& ms = m_meshes[m];
  double t = kInf;
  uint32_t key = 0;
  if (!mesh.is_static) {
    const MeshSegment seg = m_scene.segment_at(m, m_now);
    if (seg.index < mesh.key_count()) {
      key = seg.index;
      t = mesh.key_times[key];
    }
  }
  set_event(ms.flightplan, t, EventKey{0, kGridFlightplan, m, key}, m);
}

// ---------------------------------------------------------------------------------------------
// Pixels.

template <class Sort>
void FrustumBand<Sort>::pixel_insert(uint32_t tri, int column, int row) {
  PixelCell& p = cell(column, row);
  const size_t bytes = p.order.memory_bytes();
  p.order.insert(tri, m_now);
  m_pixel_bytes += p.order.memory_bytes() - bytes;
  ++m_pixel_entries;
  ++m_stats.coverage_changes;
  if (refresh_front(column, row)) m_front_changed = true;
  if (m_config.audit) audit_pixel(column, row, m_now);
}

template <class Sort>
void FrustumBand<Sort>::pixel_erase(uint32_t tri, int column, int row) {
  PixelCell& p = cell(column, row);
  const size_t bytes = p.order.memory_bytes();
  p.order.erase(tri, m_now);
  m_pixel_bytes -= bytes - p.order.memory_bytes();
  --m_pixel_entries;
  ++m_stats.coverage_changes;
  if (refresh_front(column, row)) m_front_changed = true;
  if (m_config.audit) audit_pixel(column, row, m_now);
}

// ---------------------------------------------------------------------------------------------
// Records.

template <class Sort>
uint32_t FrustumBand<Sort>::find_record(uint32_t tri, int row) const {
  for (uint32_t rec = m_triangles[tri].head; rec != kNoRecord; rec = m_records[rec].next)
    if (m_records[rec].row == row) return rec;
  return kNoRecord;
}

template <class Sort>
void FrustumBand<Sort>::set_coverage(uint32_t rec, int lo, int hi) {
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

template <class Sort>
uint32_t FrustumBand<Sort>::create_record(uint32_t tri, int row, int edge_a, int edge_b,
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
  const CoverageRule rule = first ? CoverageRule(tn.motion, tn.s)
                                  : CoverageRule(tn.motion, tn.s, ts.orientation);
  if (first) {
    ts.orientation = int8_t(rule.orientation_sign());
    if (tn.moving) ++m_live_orientations;
    schedule_orientation(tri, tn);
  }
  const auto [lo, hi] = scan_coverage(m_records[rec], rule, false);
  set_coverage(rec, lo, hi);
  return rec;
}

template <class Sort>
void FrustumBand<Sort>::kill_record(uint32_t rec) {
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
    if (ts.event != kNoEvent) m_queue.erase(ts.event);
    ts.event = kNoEvent;
    ts.orientation = 0;
    if (moving) --m_live_orientations;
  }
  r.next = kNoRecord;
  r.triangle = ~0u;
  m_free_records.push_back(rec);
  ++m_stats.records_died;
}

template <class Sort>
void FrustumBand<Sort>::rebuild_record(uint32_t rec, const TriangleNow& tn, bool full) {
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

template <class Sort>
void FrustumBand<Sort>::rescan_record(uint32_t rec, const TriangleNow& tn, bool full) {
  const CoverageRule rule(tn.motion, tn.s);
  const auto [lo, hi] = scan_coverage(m_records[rec], rule, full);
  set_coverage(rec, lo, hi);
}

template <class Sort>
bool FrustumBand<Sort>::covers_now(uint32_t rec, int column, double s) const {
  const RowRecord& r = m_records[rec];
  // The triangle's orientation sign is kept up to date by its orientation events (a change at
  // this very instant is still pending and rebuilds the record when processed). The edge
  // normals come from the cache: covers_in_row of the triangle's motion, bit for bit.
  const int o = m_triangles[r.triangle].orientation;
  if (o == 0) return false;
  const double x = m_scene.column_x(column), y = m_scene.row_y(r.row);
  auto sign_of = [&](int e) {
    const EdgeNormal& n = m_motion.edge_normal(m_scene.edge_of_triangle(r.triangle, e));
    return edge_direction(r.triangle, e) > 0 ? edge_sign(n, x, y, s)
                                             : edge_sign(n.reversed(), x, y, s);
  };
  return sign_of(r.edge[0]) == o && sign_of(r.edge[1]) == o;
}

template <class Sort>
void FrustumBand<Sort>::set_pixel(uint32_t rec, int column, bool covered) {
  const RowRecord& r = m_records[rec];
  if (covered == r.covers(column)) return;
  int lo = r.lo, hi = r.hi;
  if (covered) {
    if (r.empty())
      lo = hi = column;
    else if (column == r.lo - 1)
      lo = column;
    else if (column == r.hi + 1)
      hi = column;
    else
      lo = hi = -2;
  } else {
    if (r.lo == r.hi)
      lo = 0, hi = -1;
    else if (column == r.lo)
      ++lo;
    else if (column == r.hi)
      --hi;
    else
      lo = hi = -2;
  }
  if (lo == -2) {
    // Not at an end of the interval: several columns changed at one instant (degenerate).
    ++m_stats.degenerate_rebuilds;
    rebuild_record(rec, triangle_now(r.triangle), true);
    return;
  }
  set_coverage(rec, lo, hi);
}

template <class Sort>
void FrustumBand<Sort>::update_triangle_row(uint32_t tri, int row) {
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

template <class Sort>
void FrustumBand<Sort>::scan_triangle(uint32_t tri, const std::vector<RowPattern>& patterns) {
  const auto vs = m_scene.triangle_vertices(tri);
  if (vs[0] == vs[1] || vs[1] == vs[2] || vs[2] == vs[0]) return;  // never covers anything
  scan_rows(tri, mesh_patterns(tri, patterns));
}

template <class Sort>
std::array<typename FrustumBand<Sort>::RowPattern, 3> FrustumBand<Sort>::mesh_patterns(
    uint32_t tri, const std::vector<RowPattern>& patterns) const {
  const auto& vs = m_scene.triangle_vertices(tri);
  const uint32_t base = m_scene.vertex_begin(m_scene.mesh_of_triangle(tri));
  return {patterns[vs[0] - base], patterns[vs[1] - base], patterns[vs[2] - base]};
}

template <class Sort>
bool FrustumBand<Sort>::meets_rows(uint32_t tri, const std::array<RowPattern, 3>& p) const {
  const auto& vs = m_scene.triangle_vertices(tri);
  if (vs[0] == vs[1] || vs[1] == vs[2] || vs[2] == vs[0]) return false;
  // The signs are constant between consecutive slots: one row of each run decides.
  int cuts[5] = {0, p[0].slot, p[1].slot, p[2].slot, m_rows.count};
  sort_cuts(cuts);
  for (int k = 0; k + 1 < 5; ++k) {
    const int a = cuts[k];
    if (a >= cuts[k + 1]) continue;
    const int s0 = p[0].sign(a);
    if (p[1].sign(a) != s0 || p[2].sign(a) != s0) return true;
  }
  return false;
}

template <class Sort>
std::array<typename FrustumBand<Sort>::RowPattern, 3> FrustumBand<Sort>::tracked_patterns(
    uint32_t tri) const {
  const auto& vs = m_scene.triangle_vertices(tri);
  std::array<RowPattern, 3> p;
  for (int k = 0; k < 3; ++k) {
    const SlotTracker& st = m_vertices[vs[size_t(k)]];
    p[size_t(k)] = RowPattern{st.slot, st.sign_lo, st.sign_hi};
  }
  return p;
}

template <class Sort>
void FrustumBand<Sort>::watch(uint32_t tri, const std::array<RowPattern, 3>& p) {
  const TriangleNow tn = triangle_now(tri);
  TriangleState& ts = m_triangles[tri];
  ts.watched = true;
  ts.orientation = int8_t(sign_after(tn.motion.orientation(), tn.s));
  if (tn.moving) ++m_live_orientations;
  schedule_orientation(tri, tn);
  if (ts.orientation == m_scene.cull_sign_of_triangle(tri)) scan_rows(tri, p);
}

template <class Sort>
void FrustumBand<Sort>::unwatch(uint32_t tri) {
  TriangleState& ts = m_triangles[tri];
  while (ts.head != kNoRecord) kill_record(ts.head);
  if (ts.event != kNoEvent) m_queue.erase(ts.event);
  ts.event = kNoEvent;
  ts.orientation = 0;
  ts.watched = false;
  if (!m_scene.mesh(m_scene.mesh_of_triangle(tri)).is_static) --m_live_orientations;
}

template <class Sort>
void FrustumBand<Sort>::scan_rows(uint32_t tri, const std::array<RowPattern, 3>& p) {
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

// ---------------------------------------------------------------------------------------------
// Boundaries.

template <class Sort>
bool FrustumBand<Sort>::bind_boundary(uint32_t rec, int k, const SlotTracker* hint) {
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

template <class Sort>
void FrustumBand<Sort>::release_boundary(uint32_t rec, int k) {
  const uint32_t id = m_records[rec].boundary[size_t(k)];
  m_records[rec].boundary[size_t(k)] = kNoBoundary;
  EdgeBoundary& b = m_boundaries[id];
  if (b.records[0] == rec)
    b.records[0] = b.records[1];
  b.records[1] = kNoRecord;
  if (!b.unused()) return;
  if (b.tracker.event != kNoEvent) m_queue.erase(b.tracker.event);
  b.tracker.event = kNoEvent;
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

template <class Sort>
void FrustumBand<Sort>::relocate_boundary(uint32_t id, uint32_t rec) {
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

template <class Sort>
void FrustumBand<Sort>::rebuild_boundary(uint32_t id) {
  ++m_stats.degenerate_rebuilds;
  const EdgeNow en = edge_now(m_boundaries[id].edge);
  locate_boundary(m_boundaries[id], en);
  schedule_boundary(id, en);
  const std::array<uint32_t, 2> records = m_boundaries[id].records;
  for (uint32_t rec : records)
    if (rec != kNoRecord) rescan_record(rec, triangle_now(m_records[rec].triangle), true);
}

// ---------------------------------------------------------------------------------------------
// Meshes.

template <class Sort>
void FrustumBand<Sort>::insert_mesh(uint32_t m, WorkProgress* progress) {
  const GridMesh& mesh = m_scene.mesh(m);
  MeshState& ms = m_meshes[m];
  if (ms.present) return;
  ms.present = true;
  m_motion.set_segment(m, m_scene.segment_at(m, m_now));
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
  if (mesh.disappear < kInf && mesh.disappear > m_now) remove_at = mesh.disappear;
  set_event(ms.remove, remove_at, EventKey{0, kGridRemove, m, 0}, m);
}

template <class Sort>
void FrustumBand<Sort>::remove_mesh(uint32_t m) {
  const GridMesh& mesh = m_scene.mesh(m);
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
      if (st.event != kNoEvent) m_queue.erase(st.event);
      st = SlotTracker{};
      --m_live_vertices;
    }
  for (EventHandle* h : {&ms.flightplan, &ms.remove})
    if (*h != kNoEvent) {
      m_queue.erase(*h);
      *h = kNoEvent;
    }
  ms.present = false;
}

// ---------------------------------------------------------------------------------------------
// Events.

template <class Sort>
void FrustumBand<Sort>::start(double t0) {
  m_now = t0;
  for (uint32_t m = 0; m < m_scene.mesh_count(); ++m) {
    const GridMesh& mesh = m_scene.mesh(m);
    m_motion.set_segment(m, m_scene.segment_at(m, t0));
    if (mesh.present(t0)) {
      insert_mesh(m, m_config.init_progress);
    } else if (mesh.appear > t0 && mesh.disappear > mesh.appear) {
      set_event(m_meshes[m].insert, mesh.appear, EventKey{0, kGridInsert, m, 0}, m);
    }
  }
  m_stats.certificates_live_max =
      std::max(m_stats.certificates_live_max,
               2 * (m_live_boundaries + m_live_vertices) + m_live_orientations +
                   m_sort_stats.certificates_live);
}

template <class Sort>
double FrustumBand<Sort>::next_event_time() const {
  return m_queue.empty() ? kInf : m_queue.top_key().time;
}

template <class Sort>
void FrustumBand<Sort>::advance_to(double t) {
  KINRAY_CHECK_MSG(t >= m_now, "the kinetic grid cannot go back in time");
  while (!m_queue.empty() && m_queue.top_key().time <= t) {
    const EventKey key = m_queue.top_key();
    const uint64_t payload = m_queue.top_payload();
    KINRAY_CHECK_MSG(key.time >= m_now, "event scheduled in the past");
    if (key.kind == kGridBoundary) {
      // Its boundary was prefetched with the previous event: fetch the edge's end points, its
      // records and the two pixels it watches (one of them changes), while the queue is popped.
      const EdgeBoundary& b = m_boundaries[payload];
      const auto& ends = m_scene.edge_vertices(b.edge);
      __builtin_prefetch(&m_motion.vertex(ends[0]));
      __builtin_prefetch(&m_motion.vertex(ends[1]));
      for (uint32_t rec : b.records)
        if (rec != kNoRecord) __builtin_prefetch(&m_records[rec]);
      const int slot = b.tracker.slot;
      if (slot > 0) {
        __builtin_prefetch(&cell(slot - 1, b.row).order);
        __builtin_prefetch(&cell(slot, b.row).order);
      }
    }
    m_queue.pop();
    if (!m_queue.empty()) {
      // Most events are boundary events, whose payload names their boundary: fetch the next
      // event's slot and boundary while this one is processed (a wrong guess costs one prefetch).
      m_queue.prefetch(m_queue.top());
      const uint32_t id = m_queue.top_payload_hint();
      if (id < m_boundaries.size()) __builtin_prefetch(&m_boundaries[id]);
    }
    m_now = key.time;
    m_front_changed = false;
    handle(key, payload);
    const uint64_t live = 2 * (m_live_boundaries + m_live_vertices) + m_live_orientations +
                          m_sort_stats.certificates_live;
    m_stats.certificates_live_max = std::max(m_stats.certificates_live_max, live);
  }
}

template <class Sort>
void FrustumBand<Sort>::handle(const EventKey& key, uint64_t payload) {
  switch (key.kind) {
    case kGridFlightplan:
      handle_flightplans(uint32_t(payload));
      return;  // not an event of the picture
    case kGridRemove:
      m_meshes[payload].remove = kNoEvent;
      remove_mesh(uint32_t(payload));
      if (m_config.counts_meshes) ++m_stats.events.remove;
      break;
    case kGridInsert:
      m_meshes[payload].insert = kNoEvent;
      insert_mesh(uint32_t(payload));
      if (m_config.counts_meshes) ++m_stats.events.insert;
      break;
    case kGridOrientation:
      handle_orientation(uint32_t(payload));
      break;
    case kGridVertexRow:
      handle_vertex(uint32_t(payload));
      break;
    case kGridBoundary:
      handle_boundary(uint32_t(payload));
      break;
    case kGridSwap:
      handle_swap(key, payload);
      return;
    default:
      KINRAY_CHECK_MSG(false, "unknown grid event kind");
  }
  ++(m_front_changed ? m_stats.events_external : m_stats.events_internal);
}

template <class Sort>
void FrustumBand<Sort>::handle_flightplans(uint32_t first_mesh) {
  // Every mesh reaching a key at this instant switches segment first, then their certificates
  // are recomputed together (one camera key moves every mesh at once).
  std::vector<uint32_t> meshes = {first_mesh};
  while (!m_queue.empty() && m_queue.top_key().time == m_now &&
         m_queue.top_key().kind == kGridFlightplan) {
    meshes.push_back(uint32_t(m_queue.top_payload()));
    m_queue.pop();
  }
  for (uint32_t m : meshes) {
    m_meshes[m].flightplan = kNoEvent;
    m_motion.set_segment(m, m_scene.segment_at(m, m_now));
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
          cell(c, r.row).order.replace_motion(tri, m_now);
          refresh_front(c, r.row);
        }
      }
    }
  }
}

template <class Sort>
void FrustumBand<Sort>::handle_boundary(uint32_t id) {
  EdgeBoundary& b = m_boundaries[id];
  SlotTracker& st = b.tracker;
  st.event = kNoEvent;
  const EdgeNow en = edge_now(b.edge);
  const EdgeNormal& edge = m_motion.edge_normal(en.edge);
  const double y = m_scene.row_y(b.row);
  auto sign_at = [&](int c) { return edge_sign(edge, m_scene.column_x(c), y, en.s); };
  if (st.slot == kBehindEye) {
    // Back in front through the eye plane, at infinity: the off slot. Nothing visible changes.
    if (sign_plus(boundary_front(en, b.row), en.s) < 0) {
      ++m_stats.spurious;
      schedule_boundary(id, en, &edge);
      return;
    }
    ++m_stats.events.boundary;
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
    return;
  }
  // Plain ints, not a structured binding: clang 14 (the fuzz build) cannot capture one.
  const std::pair<int, int> watched = m_columns.watched(st.slot);
  const int lo = watched.first, hi = watched.second;
  const int gl = sign_at(lo), gh = hi == lo ? gl : sign_at(hi);
  const bool changed_lo = gl != st.sign_lo, changed_hi = gh != st.sign_hi;
  if (st.slot == 0 && sign_plus(boundary_front(en, b.row), en.s) < 0) {
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
  if (!changed_lo && !changed_hi) {
    ++m_stats.spurious;
    schedule_boundary(id, en, &edge);
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
    auto known = [&](int c) { return c == lo ? gl : (c == hi ? gh : sign_at(c)); };
    const int sl = known(nlo), sh = known(nhi);
    if (!SlotCircle::consistent(slot, sl, sh)) {
      rebuild_boundary(id);
      return;
    }
    st.slot = slot;
    st.sign_lo = int8_t(sl);
    st.sign_hi = int8_t(sh);
  }
  schedule_boundary(id, en, &edge);
  // The column passes from one triangle of the edge to the other: the one that loses it goes
  // first, so the pixel's order never holds both (no depth certificate between them).
  // Both triangles are on the edge's mesh segment, at its local time en.s.
  const std::array<uint32_t, 2> records = b.records;
  std::array<bool, 2> covered = {false, false};
  for (size_t k = 0; k < 2; ++k)
    if (records[k] != kNoRecord) covered[k] = covers_now(records[k], column, en.s);
  for (bool gains : {false, true})
    for (size_t k = 0; k < 2; ++k)
      if (records[k] != kNoRecord && covered[k] == gains) set_pixel(records[k], column, gains);
}

template <class Sort>
void FrustumBand<Sort>::handle_vertex(uint32_t v) {
  SlotTracker& st = m_vertices[v];
  st.event = kNoEvent;
  double s = 0;
  const PointMotion p = vertex_now(v, s);
  auto sign_at = [&](int q) { return sign_plus(row_side(p, m_scene.row_y(m_row_begin + q)), s); };
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

template <class Sort>
void FrustumBand<Sort>::handle_orientation(uint32_t tri) {
  TriangleState& ts = m_triangles[tri];
  ts.event = kNoEvent;
  const TriangleNow tn = triangle_now(tri);
  const int o = sign_after(tn.motion.orientation(), tn.s);
  if (o == ts.orientation) {
    ++m_stats.spurious;
    schedule_orientation(tri, tn);
    return;
  }
  const int cull = m_scene.cull_sign_of_triangle(tri);
  if (cull != 0 && (o == cull) != (ts.orientation == cull)) {
    // Culling: the triangle turns to face the eye (its records are born from its vertices' row
    // slots) or away (its records die); counted per record, like a rebuild.
    ts.orientation = int8_t(o);
    if (o == cull) {
      const uint64_t born = m_stats.records_born;
      scan_rows(tri, tracked_patterns(tri));
      m_stats.events.orientation += m_stats.records_born - born;
    } else {
      while (ts.head != kNoRecord) {
        ++m_stats.events.orientation;
        kill_record(ts.head);
      }
    }
    schedule_orientation(tri, tn);
    return;
  }
  ts.orientation = int8_t(o);
  for (uint32_t rec = ts.head; rec != kNoRecord; rec = m_records[rec].next) {
    ++m_stats.events.orientation;
    rebuild_record(rec, tn, false);
  }
  schedule_orientation(tri, tn);
}

template <class Sort>
void FrustumBand<Sort>::handle_swap(const EventKey& key, uint64_t payload) {
  const int row = int(key.a / uint32_t(m_width)), column = int(key.a % uint32_t(m_width));
  PixelCell& p = cell(column, row);
  const uint64_t events_before = m_sort_stats.events();
  const size_t bytes = p.order.memory_bytes();
  p.order.handle_event(payload, m_now);
  m_pixel_bytes = m_pixel_bytes - bytes + p.order.memory_bytes();
  const bool front_changed = refresh_front(column, row);
  if (m_sort_stats.events() == events_before) {
    ++m_stats.renewals;
    return;
  }
  ++m_stats.events.swap;
  ++(front_changed ? m_stats.events_external : m_stats.events_internal);
  if (m_config.audit) audit_pixel(column, row, m_now);
}

// ---------------------------------------------------------------------------------------------
// Audit and statistics.

template <class Sort>
void FrustumBand<Sort>::audit_pixel(int column, int row, double t) const {
  try {
    cell(column, row).order.audit(t);
  } catch (const KineticAuditFailure& e) {
    std::ostringstream out;
    out.precision(17);
    out << "kinetic audit: band rows [" << m_row_begin << ", " << m_row_end << ") pixel ("
        << column << ", " << row << ") at t = " << t << ": " << e.what();
    throw KineticAuditFailure(out.str());
  }
}

template <class Sort>
std::vector<std::string> FrustumBand<Sort>::audit(double t, size_t limit) const {
  std::vector<std::string> problems;
  auto report = [&](const std::string& what) {
    if (problems.size() < limit) problems.push_back(what);
  };
  auto where = [&](uint32_t tri, int row) {
    std::ostringstream out;
    out << "band rows [" << m_row_begin << ", " << m_row_end << ") t=" << t << " triangle " << tri
        << " row " << row << ": ";
    return out.str();
  };
  if (!m_queue.empty() && m_queue.top_key().time <= t)
    report("an event at or before the audit time is still pending");

  std::vector<uint32_t> expected(m_pixels.size(), 0);
  for (uint32_t m = 0; m < m_scene.mesh_count(); ++m) {
    const GridMesh& mesh = m_scene.mesh(m);
    if (m_meshes[m].present != mesh.present(t)) report("mesh presence differs from its interval");
    if (!m_meshes[m].present) continue;
    const MeshSegment seg = m_scene.segment_at(m, t);
    const MeshSegment& current = m_motion.segment(m);
    if (seg.index != current.index) report("mesh on the wrong flightplan segment");
    const uint32_t vb = m_scene.vertex_begin(m), ve = m_scene.vertex_end(m);
    std::vector<RowPattern> patterns(ve - vb);
    for (uint32_t v = vb; v < ve; ++v) {
      if (m_scene.triangles_of_vertex(v).empty()) continue;
      const PointMotion p = m_scene.vertex_motion(m, v - vb, current);
      const double s = t - current.origin;
      patterns[v - vb] = locate_vertex(p, s);
      if (mesh.is_static) continue;
      const SlotTracker& st = m_vertices[v];
      const auto [lo, hi] = m_rows.watched(st.slot);
      const int gl = sign_plus(row_side(p, m_scene.row_y(m_row_begin + lo)), s);
      const int gh = sign_plus(row_side(p, m_scene.row_y(m_row_begin + hi)), s);
      if (gl != st.sign_lo || gh != st.sign_hi || !SlotCircle::consistent(st.slot, gl, gh))
        report("vertex " + std::to_string(v) + " has a wrong row slot");
    }
    for (uint32_t tri = m_scene.triangle_begin(m); tri < m_scene.triangle_end(m); ++tri) {
      const TriangleMotion motion = m_scene.triangle_motion(tri, current);
      const double s = t - current.origin;
      const CoverageRule rule(motion, s);
      // The rows the triangle meets, from the vertex patterns.
      std::vector<int> rows;
      const auto vs = m_scene.triangle_vertices(tri);
      const int cull = m_scene.cull_sign(m);
      const bool culled = cull != 0 && rule.orientation_sign() != cull;  // faces away: no records
      if (!culled && !(vs[0] == vs[1] || vs[1] == vs[2] || vs[2] == vs[0]))
        for (int q = 0; q < m_rows.count; ++q) {
          const int a = patterns[vs[0] - vb].sign(q), b = patterns[vs[1] - vb].sign(q),
                    c = patterns[vs[2] - vb].sign(q);
          if (!(a == b && b == c)) rows.push_back(m_row_begin + q);
        }
      std::vector<int> held;
      for (uint32_t rec = m_triangles[tri].head; rec != kNoRecord; rec = m_records[rec].next) {
        const RowRecord& r = m_records[rec];
        held.push_back(r.row);
        if (r.triangle != tri) report(where(tri, r.row) + "record of another triangle in the list");
        const double y = m_scene.row_y(r.row);
        std::array<int, 3> sides;
        for (int k = 0; k < 3; ++k) sides[size_t(k)] = sign_plus(row_side(motion.v[size_t(k)], y), s);
        int crossing[2];
        if (crossing_edges(sides, crossing) == 2) {
          const bool ok = (r.edge[0] == crossing[0] && r.edge[1] == crossing[1]) ||
                          (r.edge[0] == crossing[1] && r.edge[1] == crossing[0]);
          if (!ok) report(where(tri, r.row) + "boundaries tied to the wrong edges");
        }
        for (int k = 0; k < 2; ++k) {
          const uint32_t id = r.boundary[size_t(k)];
          const bool bound = id < m_boundaries.size() &&
                            m_boundaries[id].edge == m_scene.edge_of_triangle(tri, r.edge[size_t(k)]) &&
                            m_boundaries[id].row == r.row &&
                            (m_boundaries[id].records[0] == rec || m_boundaries[id].records[1] == rec);
          if (!bound) report(where(tri, r.row) + "boundary " + std::to_string(k) + " not bound to its edge");
        }
        for (int c = 0; c < m_width; ++c) {
          const bool truth = rule.covers_in_row(m_scene.column_x(c), y, r.edge[0], r.edge[1]);
          if (truth != r.covers(c))
            report(where(tri, r.row) + "column " + std::to_string(c) + (truth ? " covered but not held" : " held but not covered"));
          if (r.covers(c)) {
            ++expected[size_t(r.row - m_row_begin) * size_t(m_width) + size_t(c)];
            if (!cell(c, r.row).order.contains(tri))
              report(where(tri, r.row) + "column " + std::to_string(c) + " missing from the pixel order");
          }
        }
      }
      std::sort(held.begin(), held.end());
      if (held != rows) report(where(tri, -1) + "records do not match the rows the triangle meets");
      // With culling the orientation is kept exactly for the triangles that meet the band's rows.
      const bool watched = cull != 0 && meets_rows(tri, mesh_patterns(tri, patterns));
      if (m_triangles[tri].watched != watched)
        report(where(tri, -1) + (watched ? "meets the band's rows but its orientation is not kept"
                                         : "orientation kept but the triangle meets no row"));
      if ((!held.empty() || watched) && m_triangles[tri].orientation != rule.orientation_sign())
        report(where(tri, -1) + "wrong orientation sign");
    }
  }
  // Every boundary in use: in its edge's list, bounding live records of its (edge, row), and in
  // the slot of its point.
  size_t in_use = 0;
  for (uint32_t id = 0; id < m_boundaries.size(); ++id) {
    const EdgeBoundary& b = m_boundaries[id];
    if (b.unused()) continue;
    ++in_use;
    const std::string at = "band rows [" + std::to_string(m_row_begin) + ", " + std::to_string(m_row_end) +
                           ") edge " + std::to_string(b.edge) + " row " + std::to_string(b.row) + ": ";
    uint32_t found = m_edge_heads[b.edge];
    while (found != kNoBoundary && found != id) found = m_boundaries[found].next;
    if (found != id) report(at + "boundary missing from its edge's list");
    for (uint32_t rec : b.records)
      if (rec != kNoRecord &&
          (rec >= m_records.size() || m_records[rec].triangle == ~0u ||
           (m_records[rec].boundary[0] != id && m_records[rec].boundary[1] != id)))
        report(at + "boundary names a record that does not hold it");
    const auto& ends = m_scene.edge_vertices(b.edge);
    const uint32_t m = m_scene.mesh_of_vertex(ends[0]);
    EdgeNow en;
    en.segment = m_motion.segment(m);
    en.p = m_scene.vertex_motion(m, ends[0] - m_scene.vertex_begin(m), en.segment);
    en.q = m_scene.vertex_motion(m, ends[1] - m_scene.vertex_begin(m), en.segment);
    en.s = t - en.segment.origin;
    const SlotTracker& st = b.tracker;
    const bool front = sign_plus(boundary_front(en, b.row), en.s) > 0;
    if (front == (st.slot == kBehindEye)) {
      report(at + (front ? "in front but marked behind the eye" : "behind the eye but in a slot"));
      continue;
    }
    if (!front) continue;
    const EdgeNormal edge = en.normal();
    const double y = m_scene.row_y(b.row);
    const auto [lo, hi] = m_columns.watched(st.slot);
    const int gl = edge_sign(edge, m_scene.column_x(lo), y, en.s);
    const int gh = edge_sign(edge, m_scene.column_x(hi), y, en.s);
    if (gl != st.sign_lo || gh != st.sign_hi || !SlotCircle::consistent(st.slot, gl, gh))
      report(at + "boundary in a wrong slot " + std::to_string(st.slot));
  }
  if (in_use + m_free_boundaries.size() != m_boundaries.size())
    report("boundaries neither in use nor free");

  uint64_t entries = 0;
  size_t pixel_bytes = 0;
  for (const PixelCell& p : m_pixels) {
    entries += p.order.size();
    pixel_bytes += p.order.memory_bytes() + sizeof(PixelDepthKeys);
  }
  if (entries != m_pixel_entries || pixel_bytes != m_pixel_bytes)
    report("the running count of pixel entries or pixel bytes is wrong");
  for (int j = m_row_begin; j < m_row_end; ++j)
    for (int i = 0; i < m_width; ++i) {
      const PixelCell& p = cell(i, j);
      if (p.order.size() != expected[size_t(j - m_row_begin) * size_t(m_width) + size_t(i)])
        report("pixel (" + std::to_string(i) + ", " + std::to_string(j) +
               ") holds triangles that do not cover it");
      audit_pixel(i, j, t);
      if (m_fronts[pixel_index(i, j)] != p.order.front().value_or(kNoFront))
        report("pixel (" + std::to_string(i) + ", " + std::to_string(j) +
               ") has a stale front in the band's front array");
    }
  return problems;
}

template <class Sort>
GridStats FrustumBand<Sort>::stats() const {
  GridStats s = m_stats;
  if (m_config.counts_meshes)
    for (uint32_t m = 0; m < m_scene.mesh_count(); ++m)
      if (m_scene.cull_sign(m) != 0 && m_meshes[m].present) ++s.meshes_culling;
  s.certificates_computed += m_sort_stats.work;
  s.certificates_live = 2 * (m_live_boundaries + m_live_vertices) + m_live_orientations +
                        m_sort_stats.certificates_live;
  s.records = m_records.size() - m_free_records.size();
  // Kept up to date by every change of a pixel order: stats() runs after every frame.
  const size_t pixel_bytes = m_pixel_bytes;
  s.pixel_entries = m_pixel_entries;
  s.pixel_memory_bytes = pixel_bytes;
  s.memory_bytes = pixel_bytes + m_queue.memory_bytes() + m_records.capacity() * sizeof(RowRecord) +
                   m_free_records.capacity() * sizeof(uint32_t) +
                   m_boundaries.capacity() * sizeof(EdgeBoundary) +
                   (m_free_boundaries.capacity() + m_edge_heads.capacity()) * sizeof(uint32_t) +
                   m_triangles.capacity() * sizeof(TriangleState) +
                   m_vertices.capacity() * sizeof(SlotTracker) + m_meshes.capacity() * sizeof(MeshState) +
                   m_motion.memory_bytes();
  return s;
}

template class FrustumBand<KineticSortedList<PixelDepthKeys>>;
template class FrustumBand<KineticTournament<PixelDepthKeys>>;
template class FrustumBand<KineticHeap<PixelDepthKeys>>;

}  // namespace kinray
