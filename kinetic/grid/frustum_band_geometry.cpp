// Geometry just after now: the motion of a triangle, an edge or a vertex on its mesh's current
// segment, and where vertices and boundaries sit among the band's row planes and columns.
#include "kinetic/grid/edge_slot.h"
#include "kinetic/grid/frustum_band.h"

namespace kinray {

FrustumBand::TriangleNow FrustumBand::triangle_now(uint32_t tri) const {
  TriangleNow tn;
  const uint32_t m = m_scene.mesh_of_triangle(tri);
  tn.segment = m_motion.segment(m);
  tn.motion = m_motion.triangle(tri);
  tn.s = m_sim.now() - tn.segment.origin;
  tn.moving = !m_scene.mesh(m).is_static;
  return tn;
}

FrustumBand::EdgeNow FrustumBand::edge_now(uint32_t edge) const {
  EdgeNow en;
  const auto& ends = m_scene.edge_vertices(edge);
  const uint32_t m = m_scene.mesh_of_vertex(ends[0]);
  en.segment = m_motion.segment(m);
  en.p = &m_motion.vertex(ends[0]);
  en.q = &m_motion.vertex(ends[1]);
  en.s = m_sim.now() - en.segment.origin;
  en.moving = !m_scene.mesh(m).is_static;
  en.edge = edge;
  return en;
}

PointMotion FrustumBand::vertex_now(uint32_t v, double& s) const {
  s = m_sim.now() - m_motion.segment(m_scene.mesh_of_vertex(v)).origin;
  return m_motion.vertex(v);
}

FrustumBand::RowPattern FrustumBand::locate_vertex(const PointMotion& p, double s) const {
  auto sign_at = [&](int q) { return row_side_sign(p, m_scene.row_y(m_row_begin + q), s); };
  RowPattern pattern;
  pattern.slot = m_rows.locate(sign_at);
  const auto [lo, hi] = m_rows.watched(pattern.slot);
  pattern.sign_lo = sign_at(lo);
  pattern.sign_hi = lo == hi ? pattern.sign_lo : sign_at(hi);
  if (!SlotCircle::consistent(pattern.slot, pattern.sign_lo, pattern.sign_hi))
    pattern.sign_hi = pattern.slot == 0 ? pattern.sign_lo : -pattern.sign_lo;
  return pattern;
}

Polynomial FrustumBand::boundary_front(const EdgeNow& en, int row) const {
  const double y = m_scene.row_y(row);
  const Polynomial z = boundary_depth(*en.p, *en.q, y);
  return sign_plus(row_side(*en.q, y), en.s) > 0 ? z : -z;
}

int FrustumBand::front_sign(const EdgeNow& en, int row) const {
  return boundary_front_sign(*en.p, *en.q, m_scene.row_y(row), en.s);
}

void FrustumBand::locate_boundary(EdgeBoundary& b, const EdgeNow& en) const {
  SlotTracker& t = b.tracker;
  if (front_sign(en, b.row) < 0) {
    t.slot = kBehindEye;
    t.sign_lo = t.sign_hi = 1;
    return;
  }
  const EdgeNormal& edge = m_motion.edge_normal(en.edge);
  const EdgeSlot located = locate_edge_slot(
      edge, m_columns, [&](int c) { return m_scene.column_x(c); }, m_scene.row_y(b.row), en.s);
  t.slot = located.slot;
  t.sign_lo = int8_t(located.sign_lo);
  t.sign_hi = int8_t(located.sign_hi);
  // A sign pattern that is not monotone (rounding of a nearly constant edge function) still
  // gets a consistent slot; the audit reports such rows if they ever matter.
  if (!SlotCircle::consistent(t.slot, t.sign_lo, t.sign_hi))
    t.sign_hi = int8_t(t.slot == 0 ? t.sign_lo : -t.sign_lo);
}

bool FrustumBand::place_boundary(EdgeBoundary& b, const EdgeNow& en,
                                 const SlotTracker& hint) const {
  // The new edge's point is the same point: on the same side of the eye, in the same slot.
  SlotTracker& t = b.tracker;
  const bool front = front_sign(en, b.row) > 0;
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

std::array<int, 3> FrustumBand::row_sides(const TriangleNow& tn, int row) const {
  const double y = m_scene.row_y(row);
  return {row_side_sign(tn.motion.v[0], y, tn.s), row_side_sign(tn.motion.v[1], y, tn.s),
          row_side_sign(tn.motion.v[2], y, tn.s)};
}

}  // namespace kinray
