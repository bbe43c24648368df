#include "kinetic/tree/frame_boxes.h"

#include <cmath>
#include <limits>

namespace kinray {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::array<float, 6> kEmpty = {kInf, kInf, kInf, -kInf, -kInf, -kInf};

/// A float <= x and a float >= x, without branches: the nearest float f is within half an ulp of
/// x, and |f| 2^-22 is at least an ulp of f (1e-30 covers the values that round to 0), so the
/// float box contains the double one; the boxes grow by about 2e-7 of their coordinates.
float round_down(double x) {
  const float f = float(x);
  return f - (std::fabs(f) * 0x1p-22f + 1e-30f);
}
float round_up(double x) {
  const float f = float(x);
  return f + (std::fabs(f) * 0x1p-22f + 1e-30f);
}

/// slab_entry for a ray with no zero direction component: every slab parameter is a number (the
/// box is not empty), so the test needs no branch per axis (they mispredict half the time).
double slab_entry_finite(const std::array<float, 6>& b, const Eigen::Vector3d& o,
                         const Eigen::Vector3d& inv, double s_min, double s_max) {
  if (!(b[0] <= b[3])) return std::numeric_limits<double>::infinity();  // absent subtree
  double lo = s_min, hi = s_max;
  for (int a = 0; a < 3; ++a) {
    const double t0 = (double(b[size_t(a)]) - o[a]) * inv[a];
    const double t1 = (double(b[size_t(a) + 3]) - o[a]) * inv[a];
    lo = std::max(lo, std::min(t0, t1));
    hi = std::min(hi, std::max(t0, t1));
  }
  return lo <= hi ? lo : std::numeric_limits<double>::infinity();
}

}  // namespace

void FrameBoxes::prepare(const BvhTopology& topology, const TreeMeshes& meshes,
                         const TreeFrame& frame) {
  const auto& nodes = topology.nodes;
  if (m_topology != &topology || m_slot.size() != nodes.size()) {
    m_topology = &topology;
    m_slot.assign(nodes.size(), kNoNode);
    std::vector<uint32_t> compact(nodes.size(), kNoNode);
    uint32_t inner = 0;
    for (uint32_t i = 0; i < nodes.size(); ++i)
      if (!nodes[i].leaf()) compact[i] = inner++;
    m_nodes.assign(inner, Node{});
    auto link = [&](uint32_t i) {
      return nodes[i].leaf() ? kLeaf | nodes[i].triangle : compact[i];
    };
    for (uint32_t i = 0; i < nodes.size(); ++i) {
      if (nodes[i].leaf()) continue;
      Node& n = m_nodes[compact[i]];
      n.link = {link(nodes[i].left), link(nodes[i].right)};
      m_slot[nodes[i].left] = compact[i] * 2;
      m_slot[nodes[i].right] = compact[i] * 2 + 1;
    }
    m_root_link = nodes.empty() ? kNoNode : link(0);
  }
  m_meshes = &meshes;
  m_frame = &frame;
}

void FrameBoxes::fill(const KineticBvh& tree, const TreeFrame& frame) {
  const TreeMeshes& meshes = tree.meshes();
  prepare(tree.topology(), meshes, frame);
  m_coordinates.resize(size_t(meshes.vertex_count()) * 3);
  for (uint32_t v = 0; v < meshes.vertex_count(); ++v)
    for (int a = 0; a < 3; ++a)
      m_coordinates[size_t(v) * 3 + size_t(a)] = meshes.coordinate(v, a, frame.t);
  const auto& nodes = tree.topology().nodes;
  if (nodes.empty()) return;
  // Pre-order: a parent's box is in place before its children's. The AABB tree tracks every side
  // of an active node, so the cut below is its own box; the BoxTree's root tracks none (the box of
  // the shot).
  const Aabb root = tree.root_box(frame);
  for (uint32_t i = 0; i < nodes.size(); ++i) {
    std::array<float, 6>& b = slot(i);
    if (!tree.active(i)) {
      b = kEmpty;
      continue;
    }
    if (i == 0) {
      for (int a = 0; a < 3; ++a) {
        b[size_t(a)] = round_down(root.lo[a]);
        b[size_t(a) + 3] = round_up(root.hi[a]);
      }
    } else {
      b = slot(nodes[i].parent);
    }
    for (int s = 0; s < 6; ++s) {
      const uint32_t r = tree.realizer(i, s);
      if (r == kNoVertex) continue;
      const int a = side_axis(s);
      const double v = m_coordinates[size_t(r) * 3 + size_t(a)];
      if (side_sign(s) > 0)
        b[size_t(a) + 3] = std::min(b[size_t(a) + 3], round_up(v + frame.pad));
      else
        b[size_t(a)] = std::max(b[size_t(a)], round_down(v - frame.pad));
    }
  }
}

void FrameBoxes::fill(const BottomUpBvh& tree, const TreeFrame& frame) {
  prepare(tree.topology(), tree.meshes(), frame);
  for (uint32_t i = 0; i < tree.topology().nodes.size(); ++i) {
    const Aabb& box = tree.box(i);
    std::array<float, 6>& b = slot(i);
    if (!(box.lo[0] <= box.hi[0])) {
      b = kEmpty;
      continue;
    }
    for (int a = 0; a < 3; ++a) {
      b[size_t(a)] = round_down(box.lo[a] - frame.pad);
      b[size_t(a) + 3] = round_up(box.hi[a] + frame.pad);
    }
  }
}

std::optional<TreeHit> frame_traverse(const FrameBoxes& boxes, const TreeRay& ray, bool any) {
  if (boxes.root_link() == kNoNode) return std::nullopt;
  const TreeMeshes& meshes = boxes.meshes();
  const Eigen::Vector3d inv = ray.direction.cwiseInverse();
  const bool finite = inv.allFinite();
  auto entry = [&](const std::array<float, 6>& b, double s_max) {
    return finite ? slab_entry_finite(b, ray.origin, inv, ray.s_min, s_max)
                  : detail::slab_entry(&b[0], &b[3], ray.origin, inv, ray.s_min, s_max);
  };
  struct Entry {
    uint32_t link;
    double entry;
  };
  Entry stack[128];
  int top = 0;
  std::optional<TreeHit> best;
  double s_max = ray.s_max;
  const double e = entry(boxes.root_box(), s_max);
  if (!(e < s_max)) return std::nullopt;
  stack[top++] = Entry{boxes.root_link(), e};
  while (top > 0) {
    const Entry cur = stack[--top];
    if (!(cur.entry < s_max)) continue;
    if ((cur.link & FrameBoxes::kLeaf) != 0) {
      const uint32_t tri = cur.link & ~FrameBoxes::kLeaf;
      if (tri == ray.skip) continue;
      const auto& v = meshes.triangle(tri);
      const std::optional<double> s = ray_triangle(ray.origin, ray.direction, boxes.position(v[0]),
                                                   boxes.position(v[1]), boxes.position(v[2]));
      if (s && *s > ray.s_min && *s < s_max) {
        best = TreeHit{tri, *s};
        if (any) return best;
        s_max = *s;
      }
      continue;
    }
    const FrameBoxes::Node& n = boxes.node(cur.link);
    for (uint32_t link : n.link)  // the next nodes' lines load while this one is tested
      if ((link & FrameBoxes::kLeaf) == 0) __builtin_prefetch(&boxes.node(link));
    const double el = entry(n.box[0], s_max), er = entry(n.box[1], s_max);
    detail::push_children(stack, top, Entry{n.link[0], el}, Entry{n.link[1], er}, s_max);
  }
  return best;
}

}  // namespace kinray
