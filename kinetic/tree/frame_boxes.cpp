#include "kinetic/tree/frame_boxes.h"

#include <emmintrin.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "kinetic/tree/ray_triangle_filter.h"
#include "kinetic/tree/wide_slab_test.h"
#include "util/check.h"

namespace kinray {

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr std::array<float, 6> kEmpty = {kInf, kInf, kInf, -kInf, -kInf, -kInf};
constexpr std::array<float, 6> kEverywhere = {-kInf, -kInf, -kInf, kInf, kInf, kInf};

/// The nearest floats of (x, y) and z, lanes x, y, z, z: a vertex point (the fourth lane unused).
__m128 nearest_floats(__m128d xy, __m128d zz) {
  return _mm_movelh_ps(_mm_cvtpd_ps(xy), _mm_cvtpd_ps(zz));
}

/// Floats >= (x, y, z) + pad (kUp) or <= (x, y, z) - pad, lanes x, y, z and one unused,
/// without branches: the nearest float f is within half an ulp of its double, and |f| 2^-22 is
/// at least an ulp of f (1e-30 covers the values that round to 0), so a float box contains the
/// double one; the boxes grow by about 2e-7 of their coordinates.
template <bool kUp>
__m128 round_outward(__m128d xy, __m128d zz, double pad) {
  const __m128d p = _mm_set1_pd(kUp ? pad : -pad);  // x - pad is exactly x + (-pad)
  const __m128 f = nearest_floats(_mm_add_pd(xy, p), _mm_add_pd(zz, p));
  const __m128 ulp = _mm_add_ps(
      _mm_mul_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), f), _mm_set1_ps(0x1p-22f)), _mm_set1_ps(1e-30f));
  return kUp ? _mm_add_ps(f, ulp) : _mm_sub_ps(f, ulp);
}
template <bool kUp>
__m128 round_outward(double x, double y, double z, double pad) {
  return round_outward<kUp>(_mm_set_pd(y, x), _mm_set1_pd(z), pad);
}

std::array<float, 6> rounded(const Aabb& box, double pad) {
  if (!(box.lo[0] <= box.hi[0])) return kEmpty;
  alignas(16) float lo[4], hi[4];
  _mm_store_ps(lo, round_outward<false>(box.lo.x(), box.lo.y(), box.lo.z(), pad));
  _mm_store_ps(hi, round_outward<true>(box.hi.x(), box.hi.y(), box.hi.z(), pad));
  return {lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]};
}

/// A float box side from a vertex point: c = the nearest float to a double coordinate x, moved
/// outward by |c| 2^-22 + pad_margin (pad_margin >= (pad + 1e-30)(1 + 2^-20), rounded up), is
/// beyond x +- pad. Why: |x - c| <= 2^-24 |c| (+ 2^-150 below the normal floats);
/// |c| 2^-22 is exact (or within 2^-150), the sum loses at most 2^-24 of itself and the final
/// sum or difference moves by at most 2^-24 (|c| + margin), which leaves at least
/// (2^-23 - 2^-45) |c| of the first term and all of pad + 2^-150 covered by the second.
/// Infinite c stays infinite on its side (a coordinate beyond the float range).
template <bool kUp>
__m128 outward(__m128 c, __m128 pad_margin) {
  const __m128 margin = _mm_add_ps(
      _mm_mul_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), c), _mm_set1_ps(0x1p-22f)), pad_margin);
  return kUp ? _mm_add_ps(c, margin) : _mm_sub_ps(c, margin);
}

/// The traversal stack: a wide node pushes at most four children for the one it pops.
constexpr int kStackSize = 512;

}  // namespace

void FrameBoxes::prepare(const BvhTopology& topology, const TreeMeshes& meshes,
                         const TreeFrame& frame) {
  m_meshes = &meshes;
  m_frame = &frame;
  m_stamp += 2;
  const auto& nodes = topology.nodes;
  if (m_topology == &topology && m_slot.size() == nodes.size()) return;
  m_topology = &topology;
  m_copy_of = nullptr;
  m_slot.assign(nodes.size(), kNoLink);
  m_nodes.clear();
  m_children.clear();
  m_root_link = nodes.empty() ? kNoLink : nodes[0].leaf() ? kLeaf | nodes[0].triangle : 0;
  if (nodes.empty() || nodes[0].leaf()) return;
  // The collapse opens the largest inner child first, which keeps the wide tree balanced.
  const FourWideTopology wide = collapse_four_wide(topology);
  m_nodes.resize(wide.binary.size());
  m_children = wide.children;
  for (uint32_t w = 0; w < wide.binary.size(); ++w) {
    Node n;
    for (int r = 0; r < 6; ++r)
      for (int k = 0; k < 4; ++k) n.bound[r][k] = kEmpty[size_t(r)];
    n.link.fill(kNoLink);
    n.binary = wide.binary[w];
    for (int k = 0; k < 4; ++k) {
      const uint32_t c = wide.children[w][size_t(k)];
      if (c == kNoNode) continue;
      m_slot[c] = w * 4 + uint32_t(k);
      n.used |= 1u << k;
      n.link[size_t(k)] = nodes[c].leaf() ? kLeaf | nodes[c].triangle : wide.wide[w][size_t(k)];
    }
    m_nodes[w] = n;
  }
}

std::array<float, 6> FrameBoxes::box(uint32_t i, const std::array<float, 6>& parent) const {
  if (m_bottom_up != nullptr) return rounded(m_bottom_up->box(i), m_frame->pad);
  const KineticBvh& tree = *m_kinetic;
  if (!tree.active(i)) return kEmpty;
  // The AABB tree tracks every side of an active node: its box is its own six sides. The
  // BoxTree cuts it out of its parent's.
  std::array<float, 6> b = tree.shape() == TreeShape::boxtree || i == 0 ? parent : kEverywhere;
  const __m128 pad_margin = _mm_set1_ps(m_margin_pad);
  for (int s = 0; s < 6; ++s) {
    const uint32_t r = tree.realizer(i, s);
    if (r == kNoVertex) continue;
    const int a = side_axis(s);
    const __m128 c = _mm_load_ps(m_vertex_point[r].c);
    alignas(16) float side[4];
    if (side_sign(s) > 0) {
      _mm_store_ps(side, outward<true>(c, pad_margin));
      b[size_t(a) + 3] = std::min(b[size_t(a) + 3], side[a]);
    } else {
      _mm_store_ps(side, outward<false>(c, pad_margin));
      b[size_t(a)] = std::max(b[size_t(a)], side[a]);
    }
  }
  return b;
}

void FrameBoxes::evaluate(uint32_t k) const {
  Node& n = m_nodes[k];
  std::atomic_ref<uint32_t> stamp(n.stamp);
  uint32_t seen = stamp.load(std::memory_order_acquire);
  while (seen != m_stamp) {
    if (seen == m_stamp + 1) {  // another query fills it
      _mm_pause();
      seen = stamp.load(std::memory_order_acquire);
      continue;
    }
    if (!stamp.compare_exchange_weak(seen, m_stamp + 1, std::memory_order_acquire)) continue;
    // The BoxTree cuts each box out of its parent's: this node's own box, the root's or the slot
    // its parent holds it in (the parent first).
    const bool cuts = m_kinetic != nullptr && m_kinetic->shape() == TreeShape::boxtree;
    std::array<float, 6> own = root_box();
    if (cuts && n.binary != 0) {
      const uint32_t slot = m_slot[n.binary];
      const Node& parent = node(slot >> 2);
      for (int r = 0; r < 6; ++r) own[size_t(r)] = parent.bound[r][slot & 3];
    }
    if (m_kinetic != nullptr && !cuts) {
      aabb_children(n, k);
      stamp.store(m_stamp, std::memory_order_release);
      return;
    }
    const auto& nodes = m_topology->nodes;
    for (int c = 0; c < 4; ++c) {
      if (((n.used >> c) & 1) == 0) continue;
      std::array<float, 6> b;
      if (cuts) {
        // The binary nodes from below this one down to the child (the collapse opened at most
        // two), each cut out of the one above.
        std::array<uint32_t, 4> path;
        int depth = 0;
        for (uint32_t i = m_children[k][size_t(c)]; i != n.binary; i = nodes[i].parent)
          path[size_t(depth++)] = i;
        b = own;
        while (depth > 0) b = box(path[size_t(--depth)], b);
      } else {
        b = box(m_children[k][size_t(c)], kEverywhere);
      }
      for (int r = 0; r < 6; ++r) n.bound[r][c] = b[size_t(r)];
    }
    stamp.store(m_stamp, std::memory_order_release);
    return;
  }
}

void FrameBoxes::aabb_children(Node& n, uint32_t k) const {
  // An inner child's low corner gathers lane x of its x-min realizer's point, y of its y-min's,
  // z of its z-min's (the high corner alike), moved outward, the four corners then transposed to
  // rows: the same floats as box(), without a scalar load per side.
  const __m128 x = _mm_castsi128_ps(_mm_setr_epi32(-1, 0, 0, 0));
  const __m128 y = _mm_castsi128_ps(_mm_setr_epi32(0, -1, 0, 0));
  const __m128 z = _mm_castsi128_ps(_mm_setr_epi32(0, 0, -1, 0));
  const __m128 pad_margin = _mm_set1_ps(m_margin_pad);
  auto gather = [&](uint32_t rx, uint32_t ry, uint32_t rz) {
    return _mm_or_ps(_mm_or_ps(_mm_and_ps(x, _mm_load_ps(m_vertex_point[rx].c)),
                               _mm_and_ps(y, _mm_load_ps(m_vertex_point[ry].c))),
                     _mm_and_ps(z, _mm_load_ps(m_vertex_point[rz].c)));
  };
  __m128 lo[4], hi[4];
  for (int c = 0; c < 4; ++c) {
    lo[c] = _mm_set1_ps(kInf);
    hi[c] = _mm_set1_ps(-kInf);
    if ((((n.used & n.present) >> c) & 1) == 0) continue;
    if ((n.link[size_t(c)] & kLeaf) != 0) {
      // A leaf's box spans its triangle's three points: the same floats as its realizers' (they
      // are the extreme vertices, and rounding to the nearest float keeps the order), or a box
      // around them, read through the triangle's vertex ids, which its triangle test will read
      // again, rather than the leaf's six realizers elsewhere in the tree.
      const auto& v = m_meshes->triangle(n.link[size_t(c)] & ~kLeaf);
      const __m128 p0 = _mm_load_ps(m_vertex_point[v[0]].c),
                   p1 = _mm_load_ps(m_vertex_point[v[1]].c),
                   p2 = _mm_load_ps(m_vertex_point[v[2]].c);
      lo[c] = outward<false>(_mm_min_ps(_mm_min_ps(p0, p1), p2), pad_margin);
      hi[c] = outward<true>(_mm_max_ps(_mm_max_ps(p0, p1), p2), pad_margin);
      continue;
    }
    // Sides 2 axis + 1 are the minima, 2 axis the maxima (side_axis, side_sign).
    const uint32_t(&r)[6] = n.realizer[c];
    if (std::find(std::begin(r), std::end(r), kNoVertex) != std::end(r)) {
      const std::array<float, 6> b = box(m_children[k][size_t(c)], kEverywhere);
      lo[c] = _mm_setr_ps(b[0], b[1], b[2], 0);
      hi[c] = _mm_setr_ps(b[3], b[4], b[5], 0);
      continue;
    }
    lo[c] = outward<false>(gather(r[1], r[3], r[5]), pad_margin);
    hi[c] = outward<true>(gather(r[0], r[2], r[4]), pad_margin);
  }
  _MM_TRANSPOSE4_PS(lo[0], lo[1], lo[2], lo[3]);
  _MM_TRANSPOSE4_PS(hi[0], hi[1], hi[2], hi[3]);
  for (int a = 0; a < 3; ++a) {
    _mm_store_ps(n.bound[a], lo[a]);
    _mm_store_ps(n.bound[a + 3], hi[a]);
  }
}

void FrameBoxes::set_root_box(const std::array<float, 6>& box) {
  for (int r = 0; r < 6; ++r) {
    m_root_bound[r][0] = box[size_t(r)];
    m_root_bound[r][1] = m_root_bound[r][2] = m_root_bound[r][3] = kEmpty[size_t(r)];
  }
}

std::optional<std::array<float, 6>> FrameBoxes::box_of(uint32_t i) const {
  if (i >= m_slot.size() || m_slot[i] == kNoLink) return std::nullopt;
  const Node& n = node(m_slot[i] >> 2);
  std::array<float, 6> b;
  for (int r = 0; r < 6; ++r) b[size_t(r)] = n.bound[r][m_slot[i] & 3];
  return b;
}

void FrameBoxes::track(KineticBvh& tree) {
  m_tracked = &tree;
  m_changes.clear();
  m_changes_dropped = true;  // what happened before this call is unknown: the next fill copies
  tree.add_realizer_observer([this, &tree](uint32_t node, int side) {
    if (m_changes_dropped) return;
    if (m_changes.size() >= tree.topology().nodes.size()) {  // more than copying afresh
      m_changes.clear();
      m_changes_dropped = true;
      return;
    }
    m_changes.push_back({node, uint32_t(side), tree.realizer(node, side)});
  });
}

void FrameBoxes::apply_changes() {
  for (const RealizerChange& c : m_changes) {
    const uint32_t slot = m_slot[c.node];
    if (slot != kNoLink) m_nodes[slot >> 2].realizer[slot & 3][c.side] = c.realizer;
  }
  m_changes.clear();
}

void FrameBoxes::copy_realizers(const KineticBvh& tree) {
  for (uint32_t k = 0; k < m_nodes.size(); ++k) {
    Node& n = m_nodes[k];
    n.present = 0;
    for (int c = 0; c < 4; ++c) {
      if (((n.used >> c) & 1) == 0) continue;
      const uint32_t i = m_children[k][size_t(c)];
      n.present |= uint32_t(tree.active(i)) << c;
      for (int s = 0; s < 6; ++s) n.realizer[c][s] = tree.realizer(i, s);
    }
  }
  m_copy_of = &tree;
  m_copy_presence = tree.presence_changes();
  m_changes.clear();
  m_changes_dropped = false;
}

void FrameBoxes::fill(const KineticBvh& tree, const TreeFrame& frame) {
  m_kinetic = &tree;
  m_bottom_up = nullptr;
  prepare(tree.topology(), tree.meshes(), frame);
  // The BoxTree's cuts read the tree's own realizers (box()); the AABB tree's nodes their copy,
  // current when the observer has followed every change since it was made.
  m_prefetch_lines = tree.shape() == TreeShape::aabb ? 4 : 2;
  if (tree.shape() == TreeShape::aabb) {
    if (m_copy_of != &tree || m_tracked != &tree || m_changes_dropped ||
        m_copy_presence != tree.presence_changes())
      copy_realizers(tree);
    else
      apply_changes();
  }
  const TreeMeshes& meshes = tree.meshes();
  m_vertex_point.resize(meshes.vertex_count());
  m_margin_pad = float_up((frame.pad + 1e-30) * (1 + 0x1p-20));
  // Every vertex's coordinates to the nearest floats, in one pass per frame: a + b (t - o) as
  // TreeMeshes::coordinate computes it, x and y in one SSE2 pair. Everything the loop reads is
  // in locals: its float stores could alias the vectors' pointers and the bounds, which the
  // compiler would then load again for every vertex.
  VertexPoint* const out = m_vertex_point.data();
  for (uint32_t m = 0; m < meshes.mesh_count(); ++m) {
    const double dt = frame.t - meshes.segment_origin(m);
    const __m128d dt2 = _mm_set1_pd(dt);
    const uint32_t begin = meshes.vertex_begin(m), end = meshes.vertex_begin(m + 1);
    if (begin == end) continue;
    const Eigen::Vector3d* const a = &meshes.key_start(begin);
    const Eigen::Vector3d* const b = &meshes.velocity(begin);
    for (uint32_t i = 0; i < end - begin; ++i) {
      const __m128d xy =
          _mm_add_pd(_mm_loadu_pd(a[i].data()), _mm_mul_pd(_mm_loadu_pd(b[i].data()), dt2));
      const __m128d zz = _mm_set1_pd(a[i].z() + b[i].z() * dt);
      _mm_store_ps(out[begin + i].c, nearest_floats(xy, zz));
    }
  }
  if (!tree.topology().nodes.empty()) set_root_box(box(0, rounded(tree.root_box(frame), 0)));
}

void FrameBoxes::fill(const BottomUpBvh& tree, const TreeFrame& frame) {
  m_kinetic = nullptr;
  m_bottom_up = &tree;
  m_prefetch_lines = 2;
  prepare(tree.topology(), tree.meshes(), frame);
  m_vertex_point.resize(tree.meshes().vertex_count());
  for (uint32_t v = 0; v < m_vertex_point.size(); ++v) {
    const Eigen::Vector3d& p = tree.position(v);
    _mm_store_ps(m_vertex_point[v].c, nearest_floats(_mm_loadu_pd(p.data()), _mm_set1_pd(p.z())));
  }
  if (!tree.topology().nodes.empty()) set_root_box(box(0, kEverywhere));
}

std::optional<TreeHit> frame_closest_hit(const FrameBoxes& boxes, const TreeRay& ray) {
  if (boxes.root_link() == FrameBoxes::kNoLink) return std::nullopt;
  const TreeMeshes& meshes = boxes.meshes();
  WideRay wide(ray.origin, ray.direction, ray.s_min, ray.s_max);
  struct Entry {
    uint32_t link;
    float entry;
  };
  Entry stack[kStackSize];
  int top = 0;
  {  // the root's box, the one used column of its rows
    float entry[4];
    if ((wide.test(boxes.root_bound(), entry) & 1) == 0) return std::nullopt;
    stack[top++] = Entry{boxes.root_link(), entry[0]};
  }
  std::optional<TreeHit> best;
  double s_max = ray.s_max;
  float s_high = wide.scaled_up(s_max);
  // Most triangles a ray reaches it misses: decided from the frame's float points where certain.
  const RayTriangleFilter filter(ray.origin, ray.direction, meshes.scale(), boxes.frame().pad);
  while (top > 0) {
    const Entry cur = stack[--top];
    if (!(cur.entry <= s_high)) continue;  // a hit nearer than this box was found meanwhile
    if ((cur.link & FrameBoxes::kLeaf) != 0) {
      // The nearest hit so far, and s_max shrinks to it.
      const uint32_t tri = cur.link & ~FrameBoxes::kLeaf;
      const std::optional<double> s = boxes.triangle_hit(tri, ray, filter, s_max);
      if (!s) continue;
      best = TreeHit{tri, *s};
      s_max = *s;
      wide.set_s_max(s_max);
      s_high = wide.scaled_up(s_max);
      continue;
    }
    const FrameBoxes::Node& n = boxes.node(cur.link);
    float entry[4];
    unsigned mask = unsigned(wide.test(n.bound, entry)) & n.used;
    KINRAY_CHECK_MSG(top + 4 <= kStackSize,
                     "tree query: the tree is deeper than the traversal stack");
    const int first = top;
    for (; mask != 0; mask &= mask - 1) {
      const int k = std::countr_zero(mask);
      const uint32_t link = n.link[size_t(k)];
      if ((link & FrameBoxes::kLeaf) == 0) boxes.prefetch(link);  // loads while the rest is tested
      // The nearest child is popped first (insertion, at most four).
      int j = top++;
      for (; j > first && stack[j - 1].entry < entry[k]; --j) stack[j] = stack[j - 1];
      stack[j] = Entry{link, entry[k]};
    }
  }
  return best;
}

}  // namespace kinray
