#include "kinetic/tree/window_bvh.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetic/tree/ray_triangle.h"
#include "util/check.h"

namespace kinray {

WindowBvh::WindowBvh(std::vector<FlightplanMesh> meshes) : m_meshes(std::move(meshes), 0.0) {}

void WindowBvh::sweep(double open, double close) {
  KINRAY_CHECK(open <= close);
  m_open = open;
  m_close = close;
  // Each vertex's path over the window: its positions at the window's ends and at its mesh's
  // keys inside (linear in between), padded by the rounding between those blends and the blend at
  // any time of the window, which the tree queries' pad bounds.
  const double pad = 1e-12 * m_meshes.scale();
  m_vertex_boxes.resize(m_meshes.vertex_count());
  std::vector<double> times;
  for (uint32_t m = 0; m < m_meshes.mesh_count(); ++m) {
    const FlightplanMesh& mesh = m_meshes.mesh(m);
    times = {open, close};
    for (double key : mesh.key_times)
      if (key > open && key < close) times.push_back(key);
    const uint32_t begin = m_meshes.vertex_begin(m);
    for (uint32_t v = 0; v < mesh.vertex_count; ++v) {
      Aabb& box = m_vertex_boxes[begin + v];
      box = Aabb{};
      for (double t : times) box.extend(mesh.position(v, t));
      box.lo.array() -= pad;
      box.hi.array() += pad;
    }
  }
  if (m_sweeps == 0) {
    // The shape, once: the builder on the first window's triangle boxes, whatever the presence.
    std::vector<Aabb> triangle_boxes(m_meshes.triangle_count());
    for (uint32_t tri = 0; tri < m_meshes.triangle_count(); ++tri)
      for (uint32_t v : m_meshes.triangle(tri)) triangle_boxes[tri].extend(m_vertex_boxes[v]);
    m_topology = build_binned_sah(triangle_boxes);
    m_boxes.resize(m_topology.nodes.size());
  }
  for (uint32_t i = uint32_t(m_topology.nodes.size()); i-- > 0;) {
    const BvhNode& n = m_topology.nodes[i];
    Aabb& b = m_boxes[i];
    b = Aabb{};
    if (n.leaf()) {
      const FlightplanMesh& mesh = m_meshes.mesh(m_meshes.mesh_of_triangle(n.triangle));
      // Present at some time of the window: [appear, disappear) meets [open, close].
      if (mesh.appear <= close && mesh.disappear > open)
        for (uint32_t v : m_meshes.triangle(n.triangle)) b.extend(m_vertex_boxes[v]);
    } else {
      b.extend(m_boxes[n.left]);
      b.extend(m_boxes[n.right]);
    }
  }
  // The traversal's floats: each side moved out by the pad that covers a ray's origin and
  // direction rounded to floats (a relative 2^-24 of coordinates within the scale, over the
  // distances inside the scene), then rounded outward.
  const float float_pad = float(1e-6 * m_meshes.scale());
  m_nodes.resize(m_topology.nodes.size());
  for (size_t i = 0; i < m_nodes.size(); ++i) {
    const BvhNode& n = m_topology.nodes[i];
    Node& out = m_nodes[i];
    for (int a = 0; a < 3; ++a) {
      const Aabb& b = m_boxes[i];
      if (!(b.lo[a] <= b.hi[a])) {  // empty: both sides at +inf, so every ray's slab is empty
        out.lo[a] = out.hi[a] = std::numeric_limits<float>::infinity();
        continue;
      }
      out.lo[a] =
          std::nextafter(float(b.lo[a]) - float_pad, -std::numeric_limits<float>::infinity());
      out.hi[a] =
          std::nextafter(float(b.hi[a]) + float_pad, std::numeric_limits<float>::infinity());
    }
    out.left = n.leaf() ? kNoNode : n.left;
    out.right_or_triangle = n.leaf() ? n.triangle : n.right;
  }
  ++m_sweeps;
}

bool WindowBvh::hits(uint32_t tri, const TreeRay& ray, double t) const {
  if (tri == ray.skip) return false;
  const FlightplanMesh& mesh = m_meshes.mesh(m_meshes.mesh_of_triangle(tri));
  if (!mesh.present(t)) return false;
  const FlightplanMesh::KeyBlend blend = mesh.blend_at(t);
  const uint32_t begin = m_meshes.vertex_begin(m_meshes.mesh_of_triangle(tri));
  const auto& v = m_meshes.triangle(tri);
  const std::optional<double> s =
      ray_triangle(ray.origin, ray.direction, mesh.position(v[0] - begin, blend),
                   mesh.position(v[1] - begin, blend), mesh.position(v[2] - begin, blend));
  return s && *s > ray.s_min && *s < ray.s_max;
}

bool WindowBvh::occluded(const TreeRay& ray, double t) const {
  KINRAY_CHECK_MSG(m_sweeps > 0 && t >= m_open && t <= m_close,
                   "window tree: a ray outside the swept window");
  if (m_nodes.empty()) return false;
  // The slab test in floats. A direction component of 0 becomes a tiny one of its sign: the
  // ray then runs parallel to the slab for any distance that matters, inside it or not.
  float origin[3], inverse[3];
  for (int a = 0; a < 3; ++a) {
    origin[a] = float(ray.origin[a]);
    float d = float(ray.direction[a]);
    if (std::abs(d) < 1e-30f) d = std::signbit(d) ? -1e-30f : 1e-30f;
    inverse[a] = 1.0f / d;
  }
  // The parameter range, widened by a few float roundings of the slab arithmetic.
  const float s_min = float(ray.s_min) * (1 - 4e-7f) - 1e-30f;
  const float s_max = float(std::min(ray.s_max, 1e30)) * (1 + 4e-7f);
  auto enters = [&](const Node& n) {
    float near = s_min, far = s_max;
    for (int a = 0; a < 3; ++a) {
      const float t0 = (n.lo[a] - origin[a]) * inverse[a];
      const float t1 = (n.hi[a] - origin[a]) * inverse[a];
      near = std::max(near, std::min(t0, t1));
      far = std::min(far, std::max(t0, t1));
    }
    return near <= far;
  };
  uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = m_nodes[stack[--top]];
    if (!enters(n)) continue;
    if (n.left == kNoNode) {
      if (hits(n.right_or_triangle, ray, t)) return true;
      continue;
    }
    KINRAY_CHECK_MSG(top + 2 <= 128, "window tree: the tree is deeper than the traversal stack");
    stack[top++] = n.right_or_triangle;
    stack[top++] = n.left;
  }
  return false;
}

bool WindowBvh::occluded_brute_force(const TreeRay& ray, double t) const {
  for (uint32_t tri = 0; tri < m_meshes.triangle_count(); ++tri)
    if (hits(tri, ray, t)) return true;
  return false;
}

}  // namespace kinray
