#pragma once
// The grid's input, indexed for the simulation: global triangle and vertex ids over all meshes,
// the vertex -> triangle adjacency, the pixel-centre coordinates, and the flightplan segments.
// Read-only once built, so every band reads it concurrently.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "kinetic/grid/grid_input.h"
#include "kinetic/grid/mesh_segments.h"
#include "kinetic/motion/triangle_motion.h"
#include "util/work_progress.h"

namespace kinray {

class GridScene {
 public:
  /// `threads` (0: all cores) only speeds up the load-time proofs; the scene does not depend on it.
  /// `progress`, when given, counts the back-face culling proof.
  explicit GridScene(GridInput input, int threads = 1, WorkProgress* progress = nullptr);

  [[nodiscard]] const PixelRays& rays() const { return m_input.rays; }
  [[nodiscard]] int width() const { return m_input.rays.width; }
  [[nodiscard]] int height() const { return m_input.rays.height; }
  [[nodiscard]] double column_x(int i) const { return m_x[size_t(i)]; }
  [[nodiscard]] double row_y(int j) const { return m_y[size_t(j)]; }

  [[nodiscard]] uint32_t mesh_count() const { return uint32_t(m_input.meshes.size()); }
  [[nodiscard]] const FlightplanMesh& mesh(uint32_t m) const { return m_input.meshes[m]; }
  [[nodiscard]] uint32_t triangle_count() const { return m_triangle_begin.back(); }
  [[nodiscard]] uint32_t vertex_count() const { return m_vertex_begin.back(); }
  [[nodiscard]] uint32_t triangle_begin(uint32_t m) const { return m_triangle_begin[m]; }
  [[nodiscard]] uint32_t triangle_end(uint32_t m) const { return m_triangle_begin[m + 1]; }
  [[nodiscard]] uint32_t vertex_begin(uint32_t m) const { return m_vertex_begin[m]; }
  [[nodiscard]] uint32_t vertex_end(uint32_t m) const { return m_vertex_begin[m + 1]; }
  [[nodiscard]] uint32_t mesh_of_triangle(uint32_t tri) const { return m_triangle_mesh[tri]; }
  [[nodiscard]] uint32_t mesh_of_vertex(uint32_t v) const { return m_vertex_mesh[v]; }
  /// Global vertex ids of a global triangle, seams welded (welded_triangles.h): a seam's two
  /// sides share their edge, so it is tracked once and its sides are ordered by their fold
  /// (pixel_depth_order.h).
  [[nodiscard]] const std::array<uint32_t, 3>& triangle_vertices(uint32_t tri) const {
    return m_triangle_vertices[tri];
  }
  /// Global ids of the triangles that use global vertex v.
  [[nodiscard]] std::span<const uint32_t> triangles_of_vertex(uint32_t v) const {
    return {m_adjacency.data() + m_adjacency_begin[v],
            m_adjacency.data() + m_adjacency_begin[v + 1]};
  }

  /// Edge e of triangle tri (from its vertex e to its vertex (e + 1) % 3) as a global edge id.
  /// The two triangles on either side of a mesh edge (the same two global vertices) share its
  /// id, so a band tracks the edge's crossings of pixel centres once for both of them; a third
  /// triangle on a non-manifold edge gets an id of its own.
  [[nodiscard]] uint32_t edge_of_triangle(uint32_t tri, int e) const {
    return m_triangle_edges[tri][size_t(e)];
  }
  /// Starts fetching what triangle_vertices(tri) and edge_of_triangle(tri, e) read.
  void prefetch_triangle(uint32_t tri) const {
    __builtin_prefetch(&m_triangle_vertices[tri]);
    __builtin_prefetch(&m_triangle_edges[tri]);
  }
  /// The end points of an edge in increasing global id order: the direction its edge function
  /// (p x q) is taken in. A triangle whose edge runs the other way sees the negated function.
  [[nodiscard]] const std::array<uint32_t, 2>& edge_vertices(uint32_t edge) const {
    return m_edge_vertices[edge];
  }
  [[nodiscard]] uint32_t edge_count() const { return uint32_t(m_edge_vertices.size()); }

  /// The segment of mesh m active just after t (a key time starts the new segment).
  [[nodiscard]] MeshSegment segment_at(uint32_t m, double t) const;
  /// The segment with this index.
  [[nodiscard]] MeshSegment segment(uint32_t m, uint32_t index) const;
  /// Vertex `local` of mesh m on segment `seg`, in the segment's local time.
  [[nodiscard]] PointMotion vertex_motion(uint32_t m, uint32_t local, const MeshSegment& seg) const;
  [[nodiscard]] TriangleMotion triangle_motion(uint32_t tri, const MeshSegment& seg) const;

  /// Back-face culling of mesh m: 0 when off, else the sign of O (TriangleMotion::orientation)
  /// of the triangles that face the eye. On only where back_face_cull_sign proves that every
  /// ray's first hit on the mesh is a triangle facing the eye, so the others never show.
  [[nodiscard]] int cull_sign(uint32_t m) const { return m_cull_sign[m]; }
  [[nodiscard]] int cull_sign_of_triangle(uint32_t tri) const {
    return m_cull_sign[m_triangle_mesh[tri]];
  }

 private:
  /// The global edge ids (edge_of_triangle, edge_vertices).
  void build_edges();

  GridInput m_input;
  std::vector<double> m_x, m_y;
  std::vector<uint32_t> m_triangle_begin, m_vertex_begin;  ///< prefix sums over meshes
  std::vector<uint32_t> m_triangle_mesh, m_vertex_mesh;
  std::vector<std::array<uint32_t, 3>> m_triangle_vertices;  ///< global vertex ids
  std::vector<uint32_t> m_adjacency_begin, m_adjacency;
  std::vector<std::array<uint32_t, 3>> m_triangle_edges;  ///< global edge ids
  std::vector<std::array<uint32_t, 2>> m_edge_vertices;
  std::vector<int8_t> m_cull_sign;  ///< per mesh
};

}  // namespace kinray
