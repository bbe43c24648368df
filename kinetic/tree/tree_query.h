#pragma once
// Ray queries at a time t through any of the trees (kinetic AABB tree, kinetic BoxTree, the
// bottom-up tree): one traversal, templated on where the boxes come from, so that a comparison
// of the trees measures their updates and their boxes, not two traversals. Boxes are evaluated
// lazily, when the traversal reaches them, and padded by the rounding between a segment's motion
// and the key blend that places the triangles (TreeMeshes::scale), so that they stay
// conservative; triangles are placed exactly as the Embree reference places them.
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "kinetic/tree/bvh_topology.h"
#include "kinetic/tree/ray_triangle.h"
#include "kinetic/tree/tree_meshes.h"
#include "util/check.h"

namespace kinray {

/// A ray origin + s direction for s_min < s < s_max; `skip` (a global triangle id) never hits.
struct TreeRay {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  double s_min = 0;
  double s_max = std::numeric_limits<double>::infinity();
  uint32_t skip = kNoNode;
};

struct TreeHit {
  uint32_t triangle = kNoNode;  ///< global triangle id (TreeMeshes)
  double s = 0;
};

/// What the queries of one frame share: the time and every mesh's key blend at it.
struct TreeFrame {
  double t = 0;
  std::vector<FlightplanMesh::KeyBlend> blends;
  double pad = 0;  ///< added on every side of every box
  TreeFrame() = default;
  TreeFrame(const TreeMeshes& meshes, double time) : t(time), pad(1e-12 * meshes.scale()) {
    meshes.blends_at(time, blends);
  }
};

namespace detail {

/// Entry parameter of the ray into the box [lo, hi] within (s_min, s_max), or +inf when it misses
/// (lo and hi: anything indexable by axis, double or float).
template <class Corner>
inline double slab_entry(const Corner& box_lo, const Corner& box_hi, const Eigen::Vector3d& o,
                         const Eigen::Vector3d& inv, double s_min, double s_max) {
  double lo = s_min, hi = s_max;
  for (int a = 0; a < 3; ++a) {
    const double blo = box_lo[a], bhi = box_hi[a];
    if (!(blo <= bhi)) return std::numeric_limits<double>::infinity();
    double t0 = (blo - o[a]) * inv[a], t1 = (bhi - o[a]) * inv[a];
    if (std::isnan(t0) || std::isnan(t1)) {  // direction 0 along a, origin on the slab's plane
      if (o[a] < blo || o[a] > bhi) return std::numeric_limits<double>::infinity();
      continue;
    }
    if (t0 > t1) std::swap(t0, t1);
    lo = std::max(lo, t0);
    hi = std::min(hi, t1);
    if (lo > hi) return std::numeric_limits<double>::infinity();
  }
  return lo;
}
inline double slab_entry(const Aabb& box, const Eigen::Vector3d& o, const Eigen::Vector3d& inv,
                         double s_min, double s_max) {
  return slab_entry(box.lo, box.hi, o, inv, s_min, s_max);
}

/// Pushes the children the ray enters before s_max, the nearer one on top (popped first); the
/// stack (128 entries) holds at most the tree's height + 1.
template <class Entry>
inline void push_children(Entry* stack, int& top, const Entry& left, const Entry& right,
                          double s_max) {
  KINRAY_CHECK_MSG(top + 2 <= 128, "tree query: the tree is deeper than the traversal stack");
  const bool left_first = left.entry <= right.entry;
  const Entry& far = left_first ? right : left;
  const Entry& near = left_first ? left : right;
  if (far.entry < s_max) stack[top++] = far;
  if (near.entry < s_max) stack[top++] = near;
}

/// The traversal: visit(triangle, s_max) returns the hit parameter or nullopt; with `any` the
/// first hit ends it, else the nearest one is kept and s_max shrinks to it.
template <class Boxes>
std::optional<TreeHit> traverse(const Boxes& boxes, const TreeRay& ray, const TreeFrame& frame,
                                bool any) {
  const auto& nodes = boxes.topology().nodes;
  if (nodes.empty()) return std::nullopt;
  const TreeMeshes& meshes = boxes.meshes();
  const Eigen::Vector3d inv = ray.direction.cwiseInverse();
  struct Entry {
    uint32_t node;
    double entry;
    Aabb box;
  };
  Entry stack[128];
  int top = 0;
  std::optional<TreeHit> best;
  double s_max = ray.s_max;
  const Aabb root = boxes.root_box(frame);
  double e = slab_entry(root, ray.origin, inv, ray.s_min, s_max);
  if (!(e < s_max)) return std::nullopt;
  stack[top++] = Entry{0, e, root};
  Aabb lbox, rbox;
  while (top > 0) {
    const Entry cur = stack[--top];
    if (!(cur.entry < s_max)) continue;
    const BvhNode& n = nodes[cur.node];
    if (n.leaf()) {
      if (n.triangle == ray.skip) continue;
      const auto& v = meshes.triangle(n.triangle);
      const std::optional<double> s =
          ray_triangle(ray.origin, ray.direction, meshes.position(v[0], frame.blends),
                       meshes.position(v[1], frame.blends), meshes.position(v[2], frame.blends));
      if (s && *s > ray.s_min && *s < s_max) {
        best = TreeHit{n.triangle, *s};
        if (any) return best;
        s_max = *s;
      }
      continue;
    }
    boxes.child_boxes(n, cur.box, frame, lbox, rbox);
    const double el = slab_entry(lbox, ray.origin, inv, ray.s_min, s_max);
    const double er = slab_entry(rbox, ray.origin, inv, ray.s_min, s_max);
    push_children(stack, top, Entry{n.left, el, lbox}, Entry{n.right, er, rbox}, s_max);
  }
  return best;
}

}  // namespace detail

/// The nearest triangle the ray meets at the frame's time (present triangles only).
template <class Boxes>
[[nodiscard]] std::optional<TreeHit> closest_hit(const Boxes& boxes, const TreeRay& ray,
                                                 const TreeFrame& frame) {
  return detail::traverse(boxes, ray, frame, false);
}

/// Whether the ray meets some present triangle (occlusion): the first hit found ends the search.
template <class Boxes>
[[nodiscard]] bool any_hit(const Boxes& boxes, const TreeRay& ray, const TreeFrame& frame) {
  return detail::traverse(boxes, ray, frame, true).has_value();
}

/// The reference: every present triangle tested (same triangle test, same placement).
[[nodiscard]] std::optional<TreeHit> brute_force_closest_hit(const TreeMeshes& meshes,
                                                             const TreeRay& ray,
                                                             const TreeFrame& frame);

}  // namespace kinray
