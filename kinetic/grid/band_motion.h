#pragma once
// Where every mesh of one band is on its flightplans: the current segment of each mesh (switched
// by the band's flightplan update events) and each vertex's motion p(s) = a + b s on it, computed
// once per segment. Everything the band builds certificates from reads the motions here, so the
// same motion gives bit-identical polynomials in initialisation, events and audits.
#include <array>
#include <cstdint>
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
        m_edges(scene.edge_count()) {}

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
    const auto& ends = m_scene->edge_vertices(edge);
    return m_edges.get(edge, m_vertices[ends[0]], m_vertices[ends[1]]);
  }

  /// N and D of triangle tri along pixel (column, row), in the local time of `origin`. A band is
  /// single-threaded, so a small memo of recent ones is safe: an insertion into a pixel's order
  /// compares the new triangle with several others, which then get their certificates.
  [[nodiscard]] const DepthPolynomials& depth(uint32_t tri, int column, int row, double origin) const {
    const MeshSegment& seg = segment_of(tri);
    for (const Memo& m : m_memo)
      if (m.tri == tri && m.column == column && m.row == row && m.segment == seg.index &&
          m.origin == origin)
        return m.p;
    Memo& m = m_memo[m_next++ % m_memo.size()];
    m.tri = tri;
    m.column = column;
    m.row = row;
    m.segment = seg.index;
    m.origin = origin;
    m.p = depth_polynomials(triangle(tri).rebased(origin - seg.origin), m_scene->column_x(column),
                            m_scene->row_y(row));
    return m.p;
  }
  /// Forgets the memo (the motions changed).
  void forget_depths() { m_memo = {}; }

  [[nodiscard]] size_t memory_bytes() const {
    return m_segments.capacity() * sizeof(MeshSegment) + m_vertices.capacity() * sizeof(PointMotion) +
           m_edges.memory_bytes();
  }

 private:
  struct Memo {
    uint32_t tri = ~0u;
    int32_t column = 0, row = 0;
    uint32_t segment = 0;
    double origin = 0;
    DepthPolynomials p;
  };
  const GridScene* m_scene;
  std::vector<MeshSegment> m_segments;
  std::vector<PointMotion> m_vertices;  ///< by global vertex id
  mutable EdgeNormalCache m_edges;      ///< by global edge id
  mutable std::array<Memo, 4> m_memo;
  mutable unsigned m_next = 0;
};

}  // namespace kinray
