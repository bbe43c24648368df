#pragma once
// Where every mesh of one band is on its flightplans: the current segment of each mesh (switched
// by the band's flightplan update events) and each vertex's motion p(s) = a + b s on it, computed
// once per segment. Everything the band builds certificates from reads the motions here, so the
// same motion gives bit-identical polynomials in initialisation, events and audits.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "kinetic/grid/edge_normal_cache.h"
#include "kinetic/grid/grid_scene.h"
#include "kinetic/motion/triangle_motion.h"

namespace kinray {

class BandMotion {
 public:
  explicit BandMotion(const GridScene& scene)
      : m_scene(&scene),
        m_segments(scene.mesh_count()),
        m_vertices(scene.vertex_count()),
        m_edges(scene.edge_count()),
        m_parts(std::bit_ceil(std::clamp<uint32_t>(scene.triangle_count(), 1, kPartsSlots))) {}

  [[nodiscard]] const GridScene& scene() const { return *m_scene; }
  /// Puts mesh m on `seg` and computes its vertices' motions there.
  void set_segment(uint32_t m, const MeshSegment& seg) {
    m_segments[m] = seg;
    forget_depths();
    m_edges.invalidate();
    const uint32_t begin = m_scene->vertex_begin(m);
    for (uint32_t v = begin; v < m_scene->vertex_end(m); ++v)
      m_vertices[v] = m_scene->vertex_motion(m, v - begin, seg);
  }
  [[nodiscard]] const MeshSegment& segment(uint32_t m) const { return m_segments[m]; }
  [[nodiscard]] const MeshSegment& segment_of(uint32_t tri) const {
    return m_segments[m_scene->mesh_of_triangle(tri)];
  }
  /// Global vertex v on its mesh's current segment.
  [[nodiscard]] const PointMotion& vertex(uint32_t v) const { return m_vertices[v]; }
  [[nodiscard]] TriangleMotion triangle(uint32_t tri) const {
    const auto& vs = m_scene->triangle_vertices(tri);
    return TriangleMotion{{m_vertices[vs[0]], m_vertices[vs[1]], m_vertices[vs[2]]}};
  }

  /// The normal p x q of global edge `edge` in its own direction (GridScene::edge_vertices),
  /// bit for bit edge_normal() of its end points' motions, built once per segment.
  [[nodiscard]] const EdgeNormal& edge_normal(uint32_t edge) const {
    return m_edges.get_lazily(edge, [&] {
      const auto& ends = m_scene->edge_vertices(edge);
      return std::pair{&m_vertices[ends[0]], &m_vertices[ends[1]]};
    });
  }
  /// Starts fetching edge_normal(edge)'s cache entry.
  void prefetch_edge_normal(uint32_t edge) const { m_edges.prefetch(edge); }

  /// N and D of triangle tri along pixel (column, row), in the local time of `origin`: N from the
  /// triangle's depth parts (kept), D their normal along the pixel's ray (six products, as
  /// EdgeNormal::along computes them). Always inlined: a call (as GCC chose once the sorted list
  /// grew a third caller of the pixel orders' certificates) cost 2% more instructions there.
  [[nodiscard, gnu::always_inline]] DepthCoefficients depth_coefficients(uint32_t tri, int column,
                                                                         int row,
                                                                         double origin) const {
    const Parts& parts = depth_parts_of(tri, origin, segment_of(tri));
    return {parts.numerator,
            parts.normal.along_coefficients(m_scene->column_x(column), m_scene->row_y(row))};
  }
  /// The same as Polynomials (depth_polynomials of the triangle's motion, bit for bit).
  [[nodiscard]] DepthPolynomials depth(uint32_t tri, int column, int row, double origin) const {
    return depth_coefficients(tri, column, row, origin).polynomials();
  }
  /// Forgets the triangles' depth parts (the motions changed).
  void forget_depths() {
    if (++m_parts_generation == 0) {  // wrapped: no stale stamp may match
      for (Parts& p : m_parts) p.stamp = 0;
      m_parts_generation = 1;
    }
  }

  /// Of memory_bytes(): the edge normals (a cache that fills as the band meets edges).
  [[nodiscard]] size_t edge_normal_bytes() const { return m_edges.memory_bytes(); }
  [[nodiscard]] size_t memory_bytes() const {
    return m_segments.capacity() * sizeof(MeshSegment) +
           m_vertices.capacity() * sizeof(PointMotion) + m_edges.memory_bytes() +
           m_parts.capacity() * sizeof(Parts);
  }

 private:
  /// A triangle's depth parts in the local time of `origin`, kept until its mesh's motions change:
  /// a pixel insert compares the new triangle with its neighbours, and the same triangles come
  /// back pixel after pixel along a silhouette or a fold, where only D's along(x, y) differs. The
  /// same function of the same motions, so the same bits. A fixed table indexed by the low bits of
  /// the triangle id (neighbouring triangles have neighbouring ids), so the memory does not grow
  /// with the scene or with what a band comes to see: at most 16,384 slots, 1.9 MB a band, fewer
  /// for a scene of fewer triangles (each band's table is zero-filled at the start). With 4,096 a
  /// band of cloth's fold rebuilt the parts at 20% of its look-ups, with 16,384 at 3%
  /// (instructions of cloth's event protocol -3.4%, wavy-sphere's unchanged).
  struct Parts {
    uint32_t tri = ~0u;
    uint32_t stamp = 0;  ///< the generation it was built in
    double origin = 0;
    std::array<double, 4> numerator{};  ///< N's coefficients (degree 3)
    EdgeNormal normal;
  };
  static constexpr uint32_t kPartsSlots = 16384;
  [[nodiscard]] const Parts& depth_parts_of(uint32_t tri, double origin,
                                            const MeshSegment& seg) const {
    Parts& p = m_parts[tri & (m_parts.size() - 1)];
    if (p.tri != tri || p.stamp != m_parts_generation || p.origin != origin) {
      const DepthParts parts = depth_parts(triangle(tri).rebased(origin - seg.origin));
      p.tri = tri;
      p.stamp = m_parts_generation;
      p.origin = origin;
      std::copy_n(parts.numerator.c.begin(), 4, p.numerator.begin());
      p.normal = parts.normal;
    }
    return p;
  }

  const GridScene* m_scene;
  std::vector<MeshSegment> m_segments;
  std::vector<PointMotion> m_vertices;  ///< by global vertex id
  mutable EdgeNormalCache m_edges;      ///< by global edge id
  mutable std::vector<Parts> m_parts;   ///< a power of two of slots
  uint32_t m_parts_generation = 1;
};

}  // namespace kinray
