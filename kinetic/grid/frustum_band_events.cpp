// The band's event loop: construction, the start at t0, advancing through the queue
// (prefetching the next boundary event), the dispatch by event kind, and the pixel orders' swap
// events.
#include "kinetic/grid/frustum_band.h"

#include <algorithm>

namespace kinray {

FrustumBand::FrustumBand(const GridScene& scene, int row_begin, int row_end, const Config& config)
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
  m_orders = PixelOrders::make(config.sort, m_motion, m_width, row_begin, row_end, m_sim.queue(),
                               kGridSwap, m_sort_stats);
  m_fronts.assign(size_t(row_end - row_begin) * size_t(m_width), kNoFront);
  m_pixel_marks.assign(m_fronts.size(), 0);
}

void FrustumBand::start(double t0) {
  m_sim.start_at(t0);
  for (uint32_t m = 0; m < m_scene.mesh_count(); ++m) {
    const FlightplanMesh& mesh = m_scene.mesh(m);
    m_motion.set_segment(m, m_scene.segment_at(m, t0));
    if (mesh.present(t0)) {
      insert_mesh(m, m_config.init_progress);
    } else if (mesh.appear > t0 && mesh.disappear > mesh.appear) {
      m_sim.queue().schedule(m_meshes[m].insert, EventKey{mesh.appear, kGridInsert, m, 0}, m);
    }
  }
  m_stats.certificates_live_max =
      std::max(m_stats.certificates_live_max,
               2 * (m_live_boundaries + m_live_vertices) + m_live_orientations +
                   m_sort_stats.certificates_live);
}

void FrustumBand::advance_to(double t) {
  // Most events are boundary events, whose payload names their boundary, and a boundary event
  // reads memory far apart: the boundary, its two records, then for each record its triangle's
  // orientation, vertices and edges and its other edge's normal (covers_now). Those are fetched
  // in stages, each a step ahead of the one that reads it, while the queue works and the
  // previous event is handled: the boundary two events ahead (the heap's second event), its
  // records one event ahead, the records' triangles and normals as the event pops. A wrong guess
  // (the next event is not a boundary event, or an event scheduled meanwhile comes first) costs
  // a few useless fetches.
  struct Prefetch {
    const FrustumBand& band;
    void before_pop(const EventKey& key, uint64_t payload) const {
      if (key.kind != kGridBoundary) return;
      const EdgeBoundary& b = band.m_boundaries[payload];
      const auto& ends = band.m_scene.edge_vertices(b.edge);
      __builtin_prefetch(&band.m_motion.vertex(ends[0]));
      __builtin_prefetch(&band.m_motion.vertex(ends[1]));
      band.m_motion.prefetch_edge_normal(b.edge);
      for (uint32_t rec : b.records)
        if (rec != kNoRecord) band.prefetch_coverage(band.m_records[rec]);
      const int slot = b.tracker.slot;
      if (slot > 0) {
        band.m_orders->prefetch(band.pixel_index(slot - 1, b.row));
        band.m_orders->prefetch(band.pixel_index(slot, b.row));
      }
    }
    void after_pop(const EventQueue& queue) const {
      const uint32_t next = queue.top_payload_hint();
      if (next < band.m_boundaries.size())
        for (uint32_t rec : band.m_boundaries[next].records)
          if (rec != kNoRecord) __builtin_prefetch(&band.m_records[rec]);
      const uint32_t second = queue.second_payload_hint();
      if (second < band.m_boundaries.size()) __builtin_prefetch(&band.m_boundaries[second]);
    }
  };
  KINRAY_CHECK_MSG(t >= m_sim.now(), "the kinetic grid cannot go back in time");
  m_sim.advance_to(
      t,
      [this](const EventKey& key, uint64_t payload) {
        m_front_changed = false;
        handle(key, payload);
        const uint64_t live = 2 * (m_live_boundaries + m_live_vertices) + m_live_orientations +
                              m_sort_stats.certificates_live;
        m_stats.certificates_live_max = std::max(m_stats.certificates_live_max, live);
      },
      Prefetch{*this});
}

void FrustumBand::handle(const EventKey& key, uint64_t payload) {
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

void FrustumBand::handle_swap(const EventKey& key, uint64_t payload) {
  const int row = int(key.a / uint32_t(m_width)), column = int(key.a % uint32_t(m_width));
  const size_t k = pixel_index(column, row);
  const uint64_t events_before = m_sort_stats.events();
  const bool front_changed = refresh_front(k, m_orders->handle_event(k, payload, m_sim.now()));
  if (m_sort_stats.events() == events_before) {
    ++m_stats.renewals;
    return;
  }
  ++m_stats.events.swap;
  ++(front_changed ? m_stats.events_external : m_stats.events_internal);
  if (m_config.audit) audit_pixel(column, row, m_sim.now());
}

}  // namespace kinray
