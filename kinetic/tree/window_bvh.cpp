#include "kinetic/tree/window_bvh.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "kinetic/tree/ray_triangle.h"
#include "kinetic/tree/wide_slab_test.h"
#include "util/check.h"

namespace kinray {

WindowBvh::WindowBvh(std::vector<FlightplanMesh> meshes) : m_meshes(std::move(meshes), 0.0) {}

void WindowBvh::sweep_vertices(double open, double close) {
  // Each vertex's path over [open, close]: its positions at the ends and at its mesh's keys
  // inside (linear in between), padded by the rounding between those blends and the blend at any
  // time of the window, which the tree queries' pad bounds.
  const double pad = 1e-12 * m_meshes.scale();
  m_vertex_boxes.resize(m_meshes.vertex_count());
  std::vector<double> times;
  std::vector<FlightplanMesh::KeyBlend> blends;
  for (uint32_t m = 0; m < m_meshes.mesh_count(); ++m) {
    const FlightplanMesh& mesh = m_meshes.mesh(m);
    times = {open, close};
    for (double key : mesh.key_times)
      if (key > open && key < close) times.push_back(key);
    // One key blend per time for the whole mesh (a search of its keys), not one per vertex.
    blends.clear();
    for (double t : times) blends.push_back(mesh.blend_at(t));
    const uint32_t begin = m_meshes.vertex_begin(m);
    for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
      Aabb& box = m_vertex_boxes[begin + v];
      box = Aabb{};
      for (const FlightplanMesh::KeyBlend& blend : blends) box.extend(mesh.position(v, blend));
      box.lo.array() -= pad;
      box.hi.array() += pad;
    }
  }
}

void WindowBvh::sweep_nodes(double open, double close, std::vector<Node>& nodes) {
  for (uint32_t i = uint32_t(m_topology.nodes.size()); i-- > 0;) {
    const BvhNode& n = m_topology.nodes[i];
    Aabb& b = m_boxes[i];
    b = Aabb{};
    if (n.leaf()) {
      const FlightplanMesh& mesh = m_meshes.mesh(m_meshes.mesh_of_triangle(n.triangle));
      // Present at some time of [open, close]: [appear, disappear) meets it.
      if (mesh.appear <= close && mesh.disappear > open)
        for (uint32_t v : m_meshes.triangle(n.triangle)) b.extend(m_vertex_boxes[v]);
    } else {
      b.extend(m_boxes[n.left]);
      b.extend(m_boxes[n.right]);
    }
  }
  // The traversal's wide nodes: each child's box rounded outward to floats.
  constexpr float kInf = std::numeric_limits<float>::infinity();
  nodes.resize(m_wide.binary.size());
  for (size_t w = 0; w < nodes.size(); ++w) {
    Node& out = nodes[w];
    for (size_t k = 0; k < 4; ++k) {
      const uint32_t c = m_wide.children[w][k];
      out.link[k] = c == kNoNode                 ? kNoNode
                    : m_topology.nodes[c].leaf() ? kLeaf | m_topology.nodes[c].triangle
                                                 : m_wide.wide[w][k];
      const Aabb* b = c == kNoNode ? nullptr : &m_boxes[c];
      for (int a = 0; a < 3; ++a) {
        const bool empty = b == nullptr || !(b->lo[a] <= b->hi[a]);
        out.bound[a][k] = empty ? kInf : float_down(b->lo[a]);
        out.bound[a + 3][k] = empty ? -kInf : float_up(b->hi[a]);
      }
    }
  }
}

void WindowBvh::sweep(double open, double close) {
  KINRAY_CHECK(open <= close);
  m_open = open;
  m_close = close;
  if (m_sweeps == 0) {
    // The shape, once: the builder on the first window's triangle boxes, whatever the presence.
    sweep_vertices(open, close);
    std::vector<Aabb> triangle_boxes(m_meshes.triangle_count());
    for (uint32_t tri = 0; tri < m_meshes.triangle_count(); ++tri)
      for (uint32_t v : m_meshes.triangle(tri)) triangle_boxes[tri].extend(m_vertex_boxes[v]);
    m_topology = build_binned_sah(triangle_boxes);
    m_boxes.resize(m_topology.nodes.size());
    m_wide = collapse_four_wide(m_topology);
    const auto& nodes = m_topology.nodes;
    m_root_link = nodes.empty() ? kNoNode : nodes[0].leaf() ? kLeaf | nodes[0].triangle : 0;
  }
  // Boxes per stratum of the window: a ray descends through those of its own time's stratum,
  // which its triangles' motion over a part of the window inflates less than over the whole (the
  // camera moves every triangle of the scene).
  for (size_t s = 0; s <= kStrata; ++s)
    m_stratum_times[s] = s == kStrata ? close : open + (close - open) * double(s) / kStrata;
  for (size_t s = 0; s < kStrata; ++s) {
    sweep_vertices(m_stratum_times[s], m_stratum_times[s + 1]);
    sweep_nodes(m_stratum_times[s], m_stratum_times[s + 1], m_strata[s]);
  }
  ++m_sweeps;
}

bool WindowBvh::hits(uint32_t tri, const TreeRay& ray, double t, MeshAtTime& at) const {
  if (tri == ray.skip) return false;
  const uint32_t m = m_meshes.mesh_of_triangle(tri);
  const FlightplanMesh& mesh = m_meshes.mesh(m);
  if (m != at.mesh) {
    at.mesh = m;
    at.present = mesh.present(t);
    at.blend = mesh.blend_at(t);
  }
  if (!at.present) return false;
  const uint32_t begin = m_meshes.vertex_begin(m);
  const auto& v = m_meshes.triangle(tri);
  const std::optional<double> s =
      ray_triangle(ray.origin, ray.direction, mesh.position(v[0] - begin, at.blend),
                   mesh.position(v[1] - begin, at.blend), mesh.position(v[2] - begin, at.blend));
  return s && *s > ray.s_min && *s < ray.s_max;
}

uint32_t WindowBvh::occluder(const TreeRay& ray, double t, uint32_t hint) const {
  KINRAY_CHECK_MSG(m_sweeps > 0 && t >= m_open && t <= m_close,
                   "window tree: a ray outside the swept window");
  MeshAtTime at;
  if (hint < m_meshes.triangle_count() && hits(hint, ray, t, at)) return hint;
  if (m_root_link == kNoNode) return kNoNode;
  // The stratum whose times [m_stratum_times[s], m_stratum_times[s + 1]] hold t.
  const auto above = std::upper_bound(m_stratum_times.begin() + 1, m_stratum_times.end() - 1, t);
  const std::vector<Node>& nodes = m_strata[size_t(above - m_stratum_times.begin()) - 1];
  const WideRay wide_ray(ray.origin, ray.direction, ray.s_min, ray.s_max);
  uint32_t stack[256];
  int top = 0;
  stack[top++] = m_root_link;
  float entry[4];
  while (top > 0) {
    const uint32_t link = stack[--top];
    if (link & kLeaf) {
      if (hits(link & ~kLeaf, ray, t, at)) return link & ~kLeaf;
      continue;
    }
    const Node& n = nodes[link];
    KINRAY_CHECK_MSG(top + 4 <= 256, "window tree: the tree is deeper than the traversal stack");
    for (int enter = wide_ray.test(n.bound, entry); enter != 0; enter &= enter - 1)
      stack[top++] = n.link[size_t(std::countr_zero(unsigned(enter)))];
  }
  return kNoNode;
}

bool WindowBvh::occluded_brute_force(const TreeRay& ray, double t) const {
  for (uint32_t tri = 0; tri < m_meshes.triangle_count(); ++tri)
    if (MeshAtTime at; hits(tri, ray, t, at)) return true;
  return false;
}

}  // namespace kinray
