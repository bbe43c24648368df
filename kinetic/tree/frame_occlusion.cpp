#include "kinetic/tree/frame_occlusion.h"

#include <array>
#include <bit>
#include <optional>

#include "kinetic/tree/wide_slab_test.h"
#include "util/check.h"

namespace kinray {

namespace {

/// Rays in flight: enough steps of the others to cover a node's load from memory (~150-200 ns
/// where the nodes miss every cache, a step some 30-60 ns of work).
constexpr size_t kLanes = 8;
/// A wide node pops one entry and pushes at most four: the stack holds at most three per level
/// of the tree and one (frame_closest_hit's bound).
constexpr int kStackSize = 512;

/// One ray's traversal: the wide nodes still to visit (an any-hit query keeps no entry
/// parameters: its interval never shrinks, so every pushed node stays worth visiting).
struct Lane {
  Lane(const FrameBoxes& boxes, const TreeRay& r, size_t i)
      : ray(&r),
        index(i),
        wide(r.origin, r.direction, r.s_min, r.s_max),
        filter(r.origin, r.direction, boxes.meshes().scale(), boxes.frame().pad) {}
  const TreeRay* ray;
  size_t index;
  WideRay wide;
  RayTriangleFilter filter;
  int top = 0;
  uint32_t stack[kStackSize];
};

enum class Step { more, hit, missed };

/// Visits the lane's next node: tests its children, a leaf met at once (a hit ends the ray),
/// an inner child met pushed and its lines requested.
Step step(const FrameBoxes& boxes, Lane& lane) {
  const FrameBoxes::Node& n = boxes.node(lane.stack[--lane.top]);
  float entry[4];
  unsigned mask = unsigned(lane.wide.test(n.bound, entry)) & n.used;
  KINRAY_CHECK_MSG(lane.top + 4 <= kStackSize,
                   "tree query: the tree is deeper than the traversal stack");
  for (; mask != 0; mask &= mask - 1) {
    const uint32_t link = n.link[size_t(std::countr_zero(mask))];
    if ((link & FrameBoxes::kLeaf) != 0) {
      if (boxes.triangle_hit(link & ~FrameBoxes::kLeaf, *lane.ray, lane.filter, lane.ray->s_max))
        return Step::hit;
    } else {
      boxes.prefetch(link);
      lane.stack[lane.top++] = link;
    }
  }
  return lane.top > 0 ? Step::more : Step::missed;
}

}  // namespace

void frame_occluded(const FrameBoxes& boxes, std::span<const TreeRay> rays,
                    std::span<uint8_t> blocked) {
  KINRAY_CHECK_MSG(rays.size() == blocked.size(), "frame_occluded: one answer per ray");
  const uint32_t root = boxes.root_link();
  std::array<std::optional<Lane>, kLanes> lanes;
  size_t next = 0;
  // Takes rays from `next` into the free lane until one needs a traversal (most enter the root
  // box; a root that is a leaf, or a ray that misses the root's box, is answered here).
  auto start = [&](std::optional<Lane>& lane) {
    while (!lane && next < rays.size()) {
      const size_t i = next++;
      blocked[i] = 0;
      if (root == FrameBoxes::kNoLink) continue;
      Lane& l = lane.emplace(boxes, rays[i], i);
      float entry[4];
      if ((l.wide.test(boxes.root_bound(), entry) & 1) == 0) {
        lane.reset();
      } else if ((root & FrameBoxes::kLeaf) != 0) {
        blocked[i] = boxes.triangle_hit(root & ~FrameBoxes::kLeaf, rays[i], l.filter,
                                        rays[i].s_max).has_value();
        lane.reset();
      } else {
        boxes.prefetch(root);
        l.stack[l.top++] = root;
      }
    }
  };
  for (bool busy = true; busy;) {
    busy = false;
    for (std::optional<Lane>& lane : lanes) {
      if (!lane) start(lane);
      if (!lane) continue;
      busy = true;
      const Step s = step(boxes, *lane);
      if (s == Step::more) continue;
      blocked[lane->index] = s == Step::hit;
      lane.reset();
    }
  }
}

}  // namespace kinray
