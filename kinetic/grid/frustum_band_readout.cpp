// Read-out of the band's statistics (the fronts and depth orders are read inline, see
// frustum_band.h).
#include "kinetic/grid/frustum_band.h"

namespace kinray {

GridStats FrustumBand::stats() const {
  GridStats s = m_stats;
  if (m_config.counts_meshes)
    for (uint32_t m = 0; m < m_scene.mesh_count(); ++m)
      if (m_scene.cull_sign(m) != 0 && m_meshes[m].present) ++s.meshes_culling;
  s.certificates_computed += m_sort_stats.work;
  s.exact_deferred += m_sort_stats.exact_deferred;
  s.certificates_live = 2 * (m_live_boundaries + m_live_vertices) + m_live_orientations +
                        m_sort_stats.certificates_live;
  s.records = m_records.size() - m_free_records.size();
  // Kept up to date by every change of a pixel order: stats() runs after every frame.
  const size_t pixel_bytes = m_orders->memory_bytes();
  s.pixel_entries = m_orders->entries();
  s.pixel_memory_bytes = pixel_bytes;
  s.edge_normal_bytes = m_motion.edge_normal_bytes();
  s.memory_bytes = pixel_bytes + m_sim.queue().memory_bytes() + m_records.capacity() * sizeof(RowRecord) +
                   m_free_records.capacity() * sizeof(uint32_t) +
                   m_boundaries.capacity() * sizeof(EdgeBoundary) +
                   (m_free_boundaries.capacity() + m_edge_heads.capacity()) * sizeof(uint32_t) +
                   m_triangles.capacity() * sizeof(TriangleState) +
                   m_vertices.capacity() * sizeof(SlotTracker) + m_meshes.capacity() * sizeof(MeshState) +
                   m_motion.memory_bytes();
  return s;
}

}  // namespace kinray
