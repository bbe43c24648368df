#include "kinetic/tree/bvh_topology.h"

#include <algorithm>
#include <numeric>

namespace kinray {

namespace {

constexpr int kBins = 16;

struct Builder {
  std::span<const Aabb> boxes;
  std::vector<Eigen::Vector3d> centroids;
  std::vector<uint32_t> order;  ///< triangle ids, partitioned in place
  BvhTopology out;

  /// The median along the widest axis of the centroids.
  std::pair<int, size_t> median_split(size_t begin, size_t end) {
    Aabb cbox;
    for (size_t i = begin; i < end; ++i) cbox.extend(centroids[order[i]]);
    Eigen::Index axis = 0;
    (cbox.hi - cbox.lo).cwiseMax(0.0).maxCoeff(&axis);
    const size_t mid = begin + (end - begin) / 2;
    std::nth_element(order.begin() + long(begin), order.begin() + long(mid),
                     order.begin() + long(end), [&](uint32_t a, uint32_t b) {
                       return centroids[a][axis] < centroids[b][axis] ||
                              (centroids[a][axis] == centroids[b][axis] && a < b);
                     });
    return {int(axis), mid};
  }

  /// Where to split order[begin, end): the axis and the index of the first right triangle.
  std::pair<int, size_t> split(size_t begin, size_t end) {
    Aabb cbox;
    for (size_t i = begin; i < end; ++i) cbox.extend(centroids[order[i]]);
    double best = std::numeric_limits<double>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = cbox.lo[axis], extent = cbox.hi[axis] - lo;
      if (!(extent > 0)) continue;
      std::array<Aabb, kBins> bins;
      std::array<size_t, kBins> counts{};
      const double scale = kBins / extent;
      for (size_t i = begin; i < end; ++i) {
        const int b = std::min(kBins - 1, int((centroids[order[i]][axis] - lo) * scale));
        bins[size_t(b)].extend(boxes[order[i]]);
        ++counts[size_t(b)];
      }
      std::array<double, kBins> right_cost{};
      Aabb acc;
      size_t count = 0;
      for (int b = kBins - 1; b > 0; --b) {
        acc.extend(bins[size_t(b)]);
        count += counts[size_t(b)];
        right_cost[size_t(b)] = count > 0 ? acc.half_area() * double(count) : 0.0;
      }
      acc = Aabb{};
      count = 0;
      for (int b = 0; b < kBins - 1; ++b) {
        acc.extend(bins[size_t(b)]);
        count += counts[size_t(b)];
        if (count == 0 || count == end - begin) continue;
        const double cost = acc.half_area() * double(count) + right_cost[size_t(b + 1)];
        if (cost < best) {
          best = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    if (best_axis < 0) return median_split(begin, end);  // every centroid in one bin
    const double lo = cbox.lo[best_axis], scale = kBins / (cbox.hi[best_axis] - lo);
    const auto mid =
        std::partition(order.begin() + long(begin), order.begin() + long(end), [&](uint32_t t) {
          return std::min(kBins - 1, int((centroids[t][best_axis] - lo) * scale)) <= best_bin;
        });
    return {best_axis, size_t(mid - order.begin())};
  }

  uint32_t build(size_t begin, size_t end, uint32_t parent, int depth) {
    const auto index = uint32_t(out.nodes.size());
    out.nodes.push_back(BvhNode{});
    out.nodes[index].parent = parent;
    if (end - begin == 1) {
      out.nodes[index].triangle = order[begin];
      return index;
    }
    // Past depth 64 the median: the height stays within the queries' fixed stacks.
    const auto [axis, mid] = depth < 64 ? split(begin, end) : median_split(begin, end);
    out.nodes[index].axis = uint8_t(axis);
    const uint32_t left = build(begin, mid, index, depth + 1);
    const uint32_t right = build(mid, end, index, depth + 1);
    out.nodes[index].left = left;
    out.nodes[index].right = right;
    return index;
  }
};

}  // namespace

FourWideTopology collapse_four_wide(const BvhTopology& topology) {
  const auto& nodes = topology.nodes;
  FourWideTopology out;
  if (nodes.empty() || nodes[0].leaf()) return out;
  // Leaves below each node (children have larger indices).
  std::vector<uint32_t> leaves(nodes.size(), 1);
  for (uint32_t i = uint32_t(nodes.size()); i-- > 0;)
    if (!nodes[i].leaf()) leaves[i] = leaves[nodes[i].left] + leaves[nodes[i].right];
  struct Pending {
    uint32_t binary, wide;
  };
  std::vector<Pending> pending{{0, 0}};
  auto add = [&](uint32_t binary) {
    out.binary.push_back(binary);
    out.children.emplace_back().fill(kNoNode);
    out.wide.emplace_back().fill(kNoNode);
    return uint32_t(out.binary.size() - 1);
  };
  add(0);
  while (!pending.empty()) {
    const Pending p = pending.back();
    pending.pop_back();
    std::array<uint32_t, 4> child{nodes[p.binary].left, nodes[p.binary].right, kNoNode, kNoNode};
    int count = 2;
    while (count < 4) {
      int largest = -1;
      for (int k = 0; k < count; ++k)
        if (!nodes[child[size_t(k)]].leaf() &&
            (largest < 0 || leaves[child[size_t(k)]] > leaves[child[size_t(largest)]]))
          largest = k;
      if (largest < 0) break;
      const BvhNode& opened = nodes[child[size_t(largest)]];
      child[size_t(largest)] = opened.left;
      child[size_t(count++)] = opened.right;
    }
    out.children[p.wide] = child;
    for (int k = 0; k < count; ++k) {
      const uint32_t c = child[size_t(k)];
      if (nodes[c].leaf()) continue;
      const uint32_t w = add(c);
      out.wide[p.wide][size_t(k)] = w;
      pending.push_back({c, w});
    }
  }
  return out;
}

uint32_t BvhTopology::height() const {
  std::vector<uint32_t> depth(nodes.size(), 0);
  uint32_t h = 0;
  for (size_t i = 1; i < nodes.size(); ++i) {
    depth[i] = depth[nodes[i].parent] + 1;
    h = std::max(h, depth[i]);
  }
  return h;
}

BvhTopology build_binned_sah(std::span<const Aabb> triangle_boxes) {
  Builder b{triangle_boxes, {}, {}, {}};
  const size_t n = triangle_boxes.size();
  b.centroids.resize(n);
  for (size_t i = 0; i < n; ++i)
    b.centroids[i] = 0.5 * (triangle_boxes[i].lo + triangle_boxes[i].hi);
  b.order.resize(n);
  std::iota(b.order.begin(), b.order.end(), 0u);
  b.out.nodes.reserve(2 * n);
  if (n > 0) b.build(0, n, kNoNode, 0);
  return std::move(b.out);
}

}  // namespace kinray
