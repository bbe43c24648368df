// Scheduling: the failure time of each certificate the band keeps (boundary slots, vertex row
// slots, orientations, flightplan keys) and the event that fires at it.
#include "kinetic/grid/frustum_band.h"

#include <algorithm>
#include <limits>

#include "kinetic/core/certificate_time.h"
#include "kinetic/core/root_finding.h"

namespace kinray {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}  // namespace

double FrustumBand::failure_time(int sign, const Polynomial& f, const MeshSegment& seg) const {
  if (sign == 0) return f.is_zero() ? kInf : m_sim.now();
  // The zero polynomial reads as positive (sign_plus). An edge function that vanishes identically
  // is watched through its perturbed sign (EdgeNormal::perturbed), which can still change within
  // the segment: n_x changes sign where n is normal to d and to x, i.e. to the row plane (the edge
  // lies in it, or its line passes through the eye), and n_y, when n_x vanishes too, where n = 0.
  // Those are scheduled like any other crossing, so the slots never hold a stale perturbed sign.
  if (f.is_zero()) return sign > 0 ? kInf : m_sim.now();
  // A vertex's row side: most vertices lie outside a band's rows all segment long, and each band
  // watches every vertex at every key, so first_failure's quick answer is taken without the call.
  if (f.degree == 1 && linear_holds_through(sign > 0 ? f.c[0] : -f.c[0], sign > 0 ? f.c[1] : -f.c[1],
                                            m_sim.now() - seg.origin, seg.end - seg.origin))
    return kInf;
  return certificate_failure_time(sign, f, seg.origin, m_sim.now(), seg.end);
}

double FrustumBand::edge_failure_time(int sign, const EdgeNormal& n, const EdgeOnRay& r, double y,
                                      const MeshSegment& seg) const {
  // along(x, y)'s coefficients (EdgeOnRay's); when one is not 0 that is the perturbed
  // polynomial, stored with degree 2 and not zero, which failure_time hands on as it is.
  if (r.c0 == 0 && r.c1 == 0 && r.c2 == 0) return failure_time(sign, n.perturbed(r.x, y), seg);
  if (sign == 0) return m_sim.now();
  // r.v is Horner's value at r's s, the segment's local time of now.
  return quadratic_failure_time(sign, r.c0, r.c1, r.c2, r.v, seg.origin, m_sim.now(), seg.end);
}

void FrustumBand::schedule_boundary(uint32_t id, const EdgeNow& en, const EdgeNormal* known,
                                    const std::array<EdgeOnRay, 2>* rays) {
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
    auto ray = [&](size_t k, int column) {
      return rays != nullptr ? (*rays)[k] : EdgeOnRay(edge, m_scene.column_x(column), y, en.s);
    };
    t = edge_failure_time(st.sign_lo, edge, ray(0, lo), y, en.segment);
    if (hi != lo) t = std::min(t, edge_failure_time(st.sign_hi, edge, ray(1, hi), y, en.segment));
    // Only from the off slot (at infinity) can the point pass behind the eye.
    if (st.slot == 0) t = std::min(t, failure_time(1, boundary_front(en, b.row), en.segment));
  }
  m_stats.certificates_computed += 2;
  m_sim.queue().schedule(st.event, EventKey{t, kGridBoundary, uint32_t(b.row), b.edge}, id);
}

void FrustumBand::schedule_vertex(uint32_t v) {
  SlotTracker& st = m_vertices[v];
  double s = 0;
  const PointMotion p = vertex_now(v, s);
  const MeshSegment& seg = m_motion.segment(m_scene.mesh_of_vertex(v));
  const auto [lo, hi] = m_rows.watched(st.slot);
  // Each band reschedules every vertex of a mesh at its keys, and most lie beyond its rows all
  // segment long: failure_time's quick test of a linear certificate, taken here inline, answers
  // "never" without the call.
  const double s_end = seg.end - seg.origin;
  auto time_at = [&](int sign, int row) {
    const Polynomial f = row_side(p, m_scene.row_y(m_row_begin + row));
    const double c0 = sign > 0 ? f.c[0] : -f.c[0], c1 = sign > 0 ? f.c[1] : -f.c[1];
    if (sign != 0 && linear_holds_through(c0, c1, s, s_end)) return kInf;
    return failure_time(sign, f, seg);
  };
  double t = time_at(st.sign_lo, lo);
  if (hi != lo) t = std::min(t, time_at(st.sign_hi, hi));
  m_stats.certificates_computed += 2;
  m_sim.queue().schedule(st.event, EventKey{t, kGridVertexRow, v, 0}, v);
}

void FrustumBand::schedule_orientation(uint32_t tri, const TriangleNow& tn) {
  if (!tn.moving) return;
  TriangleState& ts = m_triangles[tri];
  // O is the zero polynomial on a segment where the triangle is degenerate throughout (a sliver
  // whose vertices are collinear over this key interval but not the last): its sign is then 0,
  // not the + that failure_time reads the zero polynomial as, so a kept sign changes now.
  const Polynomial o = tn.motion.orientation();
  const double t = o.is_zero() ? (ts.orientation == 0 ? kInf : m_sim.now())
                               : failure_time(ts.orientation, o, tn.segment);
  ++m_stats.certificates_computed;
  m_sim.queue().schedule(ts.event, EventKey{t, kGridOrientation, tri, 0}, tri);
}

void FrustumBand::schedule_flightplan(uint32_t m) {
  const FlightplanMesh& mesh = m_scene.mesh(m);
  MeshState& ms = m_meshes[m];
  double t = kInf;
  uint32_t key = 0;
  if (!mesh.is_static) {
    const MeshSegment seg = m_scene.segment_at(m, m_sim.now());
    if (seg.index < mesh.key_count()) {
      key = seg.index;
      t = mesh.key_times[key];
    }
  }
  m_sim.queue().schedule(ms.flightplan, EventKey{t, kGridFlightplan, m, key}, m);
}

}  // namespace kinray
