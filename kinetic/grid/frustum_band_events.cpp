// The band's event loop: construction, the start at t0, advancing through the queue
// (prefetching the next boundary event), the dispatch by event kind, and the pixel orders' swap
// events.
#include "kinetic/grid/frustum_band.h"

#include <algorithm>

#include "kinetic/grid/frustum_band_sorts.h"

namespace kinray {

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
      m_pixels.emplace_back(&m_motion, i, j, m_sim.queue(),
                            uint32_t(size_t(j) * size_t(m_width) + size_t(i)), sort_config);
  m_fronts.assign(pixels, kNoFront);
  for (const PixelCell& p : m_pixels) m_pixel_bytes += p.order.memory_bytes() + sizeof(PixelDepthKeys);
}

template <class Sort>
void FrustumBand<Sort>::start(double t0) {
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

template <class Sort>
void FrustumBand<Sort>::advance_to(double t) {
  // Most events are boundary events, whose payload names their boundary: while the queue pops,
  // fetch the popped boundary's edge end points, records and the two pixels it watches (one of
  // them changes), and the next event's boundary (a wrong guess costs one prefetch).
  struct Prefetch {
    const FrustumBand& band;
    void before_pop(const EventKey& key, uint64_t payload) const {
      if (key.kind != kGridBoundary) return;
      const EdgeBoundary& b = band.m_boundaries[payload];
      const auto& ends = band.m_scene.edge_vertices(b.edge);
      __builtin_prefetch(&band.m_motion.vertex(ends[0]));
      __builtin_prefetch(&band.m_motion.vertex(ends[1]));
      for (uint32_t rec : b.records)
        if (rec != kNoRecord) __builtin_prefetch(&band.m_records[rec]);
      const int slot = b.tracker.slot;
      if (slot > 0) {
        __builtin_prefetch(&band.cell(slot - 1, b.row).order);
        __builtin_prefetch(&band.cell(slot, b.row).order);
      }
    }
    void after_pop(const EventQueue& queue) const {
      const uint32_t id = queue.top_payload_hint();
      if (id < band.m_boundaries.size()) __builtin_prefetch(&band.m_boundaries[id]);
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
void FrustumBand<Sort>::handle_swap(const EventKey& key, uint64_t payload) {
  const int row = int(key.a / uint32_t(m_width)), column = int(key.a % uint32_t(m_width));
  PixelCell& p = cell(column, row);
  const uint64_t events_before = m_sort_stats.events();
  const size_t bytes = p.order.memory_bytes();
  p.order.handle_event(payload, m_sim.now());
  m_pixel_bytes = m_pixel_bytes - bytes + p.order.memory_bytes();
  const bool front_changed = refresh_front(column, row);
  if (m_sort_stats.events() == events_before) {
    ++m_stats.renewals;
    return;
  }
  ++m_stats.events.swap;
  ++(front_changed ? m_stats.events_external : m_stats.events_internal);
  if (m_config.audit) audit_pixel(column, row, m_sim.now());
}

#define KINRAY_INSTANTIATE(Sort) \
  template FrustumBand<Sort>::FrustumBand(const GridScene& scene, int row_begin, int row_end, const Config& config); \
  template void FrustumBand<Sort>::start(double t0); \
  template void FrustumBand<Sort>::advance_to(double t); \
  template void FrustumBand<Sort>::handle(const EventKey& key, uint64_t payload); \
  template void FrustumBand<Sort>::handle_swap(const EventKey& key, uint64_t payload);
KINRAY_FOR_EACH_BAND_SORT(KINRAY_INSTANTIATE)
#undef KINRAY_INSTANTIATE

}  // namespace kinray
