#include "kinetic/grid/grid_scene.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "kinetic/motion/back_face_culling.h"
#include "kinetic/motion/welded_triangles.h"

namespace kinray {

namespace {

void validate(const GridInput& input) {
  if (input.rays.width < 1 || input.rays.height < 1)
    throw std::invalid_argument("kinetic grid: the image must be at least 1x1");
  uint64_t triangles = 0, vertices = 0;
  for (size_t m = 0; m < input.meshes.size(); ++m) {
    const FlightplanMesh& mesh = input.meshes[m];
    validate_mesh(mesh, "kinetic grid mesh " + std::to_string(m) + ": ");
    triangles += mesh.triangles.size();
    vertices += mesh.vertex_count;
  }
  if (triangles >= (uint64_t{1} << 31) || vertices >= (uint64_t{1} << 31))
    throw std::invalid_argument("kinetic grid: more than 2^31 triangles or vertices");
}

}  // namespace

GridScene::GridScene(GridInput input, int threads, WorkProgress* progress)
    : m_input(std::move(input)) {
  validate(m_input);
  const PixelRays& rays = m_input.rays;
  m_x.resize(size_t(rays.width));
  m_y.resize(size_t(rays.height));
  for (int i = 0; i < rays.width; ++i) m_x[size_t(i)] = rays.x(i);
  for (int j = 0; j < rays.height; ++j) m_y[size_t(j)] = rays.y(j);

  const size_t meshes = m_input.meshes.size();
  m_triangle_begin.assign(meshes + 1, 0);
  m_vertex_begin.assign(meshes + 1, 0);
  for (size_t m = 0; m < meshes; ++m) {
    m_triangle_begin[m + 1] = m_triangle_begin[m] + uint32_t(m_input.meshes[m].triangles.size());
    m_vertex_begin[m + 1] = m_vertex_begin[m] + uint32_t(m_input.meshes[m].vertex_count);
  }
  m_triangle_mesh.resize(triangle_count());
  m_vertex_mesh.resize(vertex_count());
  for (uint32_t m = 0; m < meshes; ++m) {
    std::fill(m_triangle_mesh.begin() + m_triangle_begin[m],
              m_triangle_mesh.begin() + m_triangle_begin[m + 1], m);
    std::fill(m_vertex_mesh.begin() + m_vertex_begin[m], m_vertex_mesh.begin() + m_vertex_begin[m + 1],
              m);
  }

  m_triangle_vertices.resize(triangle_count());
  for (uint32_t m = 0; m < meshes; ++m) {
    const auto tris = welded_triangles(m_input.meshes[m]);
    for (size_t k = 0; k < tris.size(); ++k)
      for (int c = 0; c < 3; ++c)
        m_triangle_vertices[m_triangle_begin[m] + k][size_t(c)] = m_vertex_begin[m] + tris[k][size_t(c)];
  }

  // Vertex -> triangle adjacency (CSR), triangles in increasing id order.
  m_adjacency_begin.assign(size_t(vertex_count()) + 1, 0);
  for (uint32_t tri = 0; tri < triangle_count(); ++tri)
    for (uint32_t v : triangle_vertices(tri)) ++m_adjacency_begin[v + 1];
  for (size_t v = 0; v < vertex_count(); ++v) m_adjacency_begin[v + 1] += m_adjacency_begin[v];
  m_adjacency.resize(m_adjacency_begin.back());
  std::vector<uint32_t> fill(m_adjacency_begin.begin(), m_adjacency_begin.end() - 1);
  for (uint32_t tri = 0; tri < triangle_count(); ++tri) {
    const auto vs = triangle_vertices(tri);
    for (int k = 0; k < 3; ++k) {
      // A degenerate triangle may use a vertex twice: list it once.
      bool seen = false;
      for (int l = 0; l < k; ++l) seen = seen || vs[l] == vs[k];
      if (!seen) m_adjacency[fill[vs[k]]++] = tri;
    }
  }
  // Compact away the slots left by repeated vertices.
  size_t out = 0;
  for (size_t v = 0; v < vertex_count(); ++v) {
    const size_t begin = m_adjacency_begin[v], end = fill[v];
    m_adjacency_begin[v] = uint32_t(out);
    for (size_t k = begin; k < end; ++k) m_adjacency[out++] = m_adjacency[k];
  }
  m_adjacency_begin.back() = uint32_t(out);
  m_adjacency.resize(out);

  build_edges();

  m_cull_sign.resize(meshes);
  if (progress != nullptr) {
    uint64_t work = 0;
    for (const FlightplanMesh& mesh : m_input.meshes)
      work += mesh.triangles.size() * culling_proof_segments(mesh);
    progress->begin("back-face culling proof", work);
  }
  for (uint32_t m = 0; m < meshes; ++m)
    m_cull_sign[m] = int8_t(back_face_cull_sign(m_input.meshes[m], threads, progress));
}

void GridScene::build_edges() {
  // Every (triangle, edge) by its end points; equal end points follow each other after sorting,
  // and each run is cut into pairs, each pair one id. Sorting by (ends, triangle, edge) makes the
  // ids independent of anything but the triangle list.
  struct Side {
    std::array<uint32_t, 2> ends;
    uint32_t tri;
    int edge;
  };
  std::vector<Side> sides;
  sides.reserve(size_t(triangle_count()) * 3);
  for (uint32_t tri = 0; tri < triangle_count(); ++tri) {
    const auto& vs = m_triangle_vertices[tri];
    for (int e = 0; e < 3; ++e) {
      const uint32_t p = vs[size_t(kEdgeStart[e])], q = vs[size_t(kEdgeEnd[e])];
      sides.push_back(Side{{std::min(p, q), std::max(p, q)}, tri, e});
    }
  }
  std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) {
    if (a.ends != b.ends) return a.ends < b.ends;
    return a.tri != b.tri ? a.tri < b.tri : a.edge < b.edge;
  });
  m_triangle_edges.resize(triangle_count());
  m_edge_vertices.clear();
  size_t run = 0;  // position of side k in its run of equal end points
  for (size_t k = 0; k < sides.size(); ++k) {
    run = k > 0 && sides[k - 1].ends == sides[k].ends ? run + 1 : 0;
    if (run % 2 == 0) m_edge_vertices.push_back(sides[k].ends);
    m_triangle_edges[sides[k].tri][size_t(sides[k].edge)] = uint32_t(m_edge_vertices.size() - 1);
  }
}

MeshSegment GridScene::segment(uint32_t m, uint32_t index) const {
  return mesh_segment(m_input.meshes[m], index);
}

MeshSegment GridScene::segment_at(uint32_t m, double t) const {
  return mesh_segment_at(m_input.meshes[m], t);
}

PointMotion GridScene::vertex_motion(uint32_t m, uint32_t local, const MeshSegment& seg) const {
  return mesh_vertex_motion(m_input.meshes[m], local, seg);
}

TriangleMotion GridScene::triangle_motion(uint32_t tri, const MeshSegment& seg) const {
  const uint32_t m = m_triangle_mesh[tri];
  const auto& local = m_input.meshes[m].triangles[tri - m_triangle_begin[m]];
  TriangleMotion t;
  for (int k = 0; k < 3; ++k) t.v[k] = vertex_motion(m, local[k], seg);
  return t;
}

}  // namespace kinray
