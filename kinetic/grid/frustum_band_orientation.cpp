// Orientation and the culling watch: each triangle's orientation sign, kept while it has
// records or, with back-face culling, while it meets the band's rows (watched), and the
// orientation events that rebuild its records or turn them on and off.
#include "kinetic/grid/frustum_band.h"

namespace kinray {

void FrustumBand::watch(uint32_t tri, const std::array<RowPattern, 3>& p) {
  const TriangleNow tn = triangle_now(tri);
  TriangleState& ts = m_triangles[tri];
  ts.watched = true;
  ts.orientation = int8_t(sign_after(tn.motion.orientation(), tn.s));
  if (tn.moving) ++m_live_orientations;
  schedule_orientation(tri, tn);
  if (ts.orientation == m_scene.cull_sign_of_triangle(tri)) scan_rows(tri, p);
}

void FrustumBand::unwatch(uint32_t tri) {
  TriangleState& ts = m_triangles[tri];
  while (ts.head != kNoRecord) kill_record(ts.head);
  m_sim.queue().cancel(ts.event);
  ts.orientation = 0;
  ts.watched = false;
  if (!m_scene.mesh(m_scene.mesh_of_triangle(tri)).is_static) --m_live_orientations;
}

void FrustumBand::handle_orientation(uint32_t tri) {
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

}  // namespace kinray
