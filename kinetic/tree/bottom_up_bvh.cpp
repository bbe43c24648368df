#include "kinetic/tree/bottom_up_bvh.h"

namespace kinray {

BottomUpBvh::BottomUpBvh(std::vector<FlightplanMesh> meshes, double t)
    : m_meshes(std::move(meshes), t) {
  std::vector<Aabb> boxes(m_meshes.triangle_count());
  for (uint32_t tri = 0; tri < m_meshes.triangle_count(); ++tri)
    for (uint32_t v : m_meshes.triangle(tri))
      boxes[tri].extend(Eigen::Vector3d(m_meshes.coordinate(v, 0, t), m_meshes.coordinate(v, 1, t),
                                        m_meshes.coordinate(v, 2, t)));
  m_topology = build_binned_sah(boxes);
  m_boxes.resize(m_topology.nodes.size());
  m_positions.resize(m_meshes.vertex_count());
  update(t);
}

void BottomUpBvh::update(double t) {
  m_time = t;
  m_meshes.blends_at(t, m_blends);
  for (uint32_t v = 0; v < m_meshes.vertex_count(); ++v)
    m_positions[v] = m_meshes.position(v, m_blends);
  for (uint32_t i = uint32_t(m_topology.nodes.size()); i-- > 0;) {
    const BvhNode& n = m_topology.nodes[i];
    Aabb& b = m_boxes[i];
    if (n.leaf()) {
      b = Aabb{};
      if (m_meshes.mesh(m_meshes.mesh_of_triangle(n.triangle)).present(t))
        for (uint32_t v : m_meshes.triangle(n.triangle)) b.extend(m_positions[v]);
    } else {
      b.lo = m_boxes[n.left].lo.cwiseMin(m_boxes[n.right].lo);
      b.hi = m_boxes[n.left].hi.cwiseMax(m_boxes[n.right].hi);
    }
  }
  m_box_updates += m_topology.nodes.size();
  ++m_updates;
}

size_t BottomUpBvh::memory_bytes() const {
  return m_topology.nodes.capacity() * sizeof(BvhNode) + m_boxes.capacity() * sizeof(Aabb) +
         m_positions.capacity() * sizeof(Eigen::Vector3d) +
         size_t(m_meshes.triangle_count()) * 4 * sizeof(uint32_t);
}

}  // namespace kinray
