#include "kinetic/collision/swept_volume_hierarchy.h"

#include <algorithm>

namespace kinray {
namespace {
constexpr std::uint32_t kLeafSize = 4;
}  // namespace

Eigen::AlignedBox3d swept_box(const MeshSweep& mesh, std::uint32_t t) {
  Eigen::AlignedBox3d box;
  for (std::uint32_t v : mesh.triangles[t]) {
    box.extend(mesh.start[v]);
    box.extend(mesh.end[v]);
  }
  return box;
}

std::uint32_t SweptVolumeHierarchy::build(std::uint32_t first, std::uint32_t count) {
  const std::uint32_t index = static_cast<std::uint32_t>(m_nodes.size());
  m_nodes.emplace_back();
  Eigen::AlignedBox3d box, centres;
  for (std::uint32_t i = first; i < first + count; ++i) {
    box.extend(m_boxes[m_order[i]]);
    centres.extend(m_boxes[m_order[i]].center());
  }
  m_nodes[index].box = box;
  if (count <= kLeafSize) {
    m_nodes[index].first = first;
    m_nodes[index].count = count;
    return index;
  }
  // median split on the widest axis of the centres
  Eigen::Index axis = 0;
  centres.sizes().maxCoeff(&axis);
  const auto begin = m_order.begin() + first;
  std::nth_element(begin, begin + count / 2, begin + count, [&](std::uint32_t x, std::uint32_t y) {
    return m_boxes[x].center()[axis] < m_boxes[y].center()[axis];
  });
  const std::uint32_t left = build(first, count / 2);
  const std::uint32_t right = build(first + count / 2, count - count / 2);
  m_nodes[index].left = left;
  m_nodes[index].right = right;
  return index;
}

void SweptVolumeHierarchy::update(const MeshSweep& mesh, double pad) {
  const std::uint32_t n = static_cast<std::uint32_t>(mesh.triangles.size());
  m_boxes.resize(n);
  const Eigen::Vector3d grow = Eigen::Vector3d::Constant(pad);
  for (std::uint32_t t = 0; t < n; ++t) {
    m_boxes[t] = swept_box(mesh, t);
    m_boxes[t].min() -= grow;
    m_boxes[t].max() += grow;
  }
  if (m_order.size() != n || m_nodes.empty()) {
    m_order.resize(n);
    for (std::uint32_t t = 0; t < n; ++t) m_order[t] = t;
    m_nodes.clear();
    if (n > 0) build(0, n);
    return;
  }
  // refit: children come after their parent, so a reverse sweep sees children first
  for (std::size_t i = m_nodes.size(); i-- > 0;) {
    Node& node = m_nodes[i];
    node.box.setEmpty();
    if (node.count > 0) {
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k)
        node.box.extend(m_boxes[m_order[k]]);
    } else {
      node.box.extend(m_nodes[node.left].box);
      node.box.extend(m_nodes[node.right].box);
    }
  }
}

void SweptVolumeHierarchy::contacts(const SweptVolumeHierarchy& query, const MeshSweep& a,
                                    const MeshSweep& b, double time_begin, double time_end,
                                    double window_begin, double window_end,
                                    std::vector<Contact>& out, ContactCounters& counters) const {
  const bool self = &query == this;
  ++counters.segments;
  if (m_nodes.empty()) return;
  const std::size_t first = out.size();
  // The primitive tests run over the check interval only, as a swept-volume method tests the
  // motion its boxes sweep; the contacts they report are the whole segment's, at the same times.
  const LocalWindow window = local_window(time_begin, time_end, window_begin, window_end);
  std::vector<std::uint32_t> stack;
  for (std::uint32_t i = 0; i < query.m_boxes.size(); ++i) {
    const Eigen::AlignedBox3d& box = query.m_boxes[i];
    stack.assign(1, 0);
    while (!stack.empty()) {
      const Node& node = m_nodes[stack.back()];
      stack.pop_back();
      ++counters.node_visits;
      if (!node.box.intersects(box)) continue;
      if (node.count == 0) {
        stack.push_back(node.left);
        stack.push_back(node.right);
        continue;
      }
      for (std::uint32_t k = node.first; k < node.first + node.count; ++k) {
        const std::uint32_t j = m_order[k];
        if (self && (j <= i || triangles_adjacent(a.triangles[i], a.triangles[j]))) continue;
        if (!m_boxes[j].intersects(box)) continue;
        ++counters.triangle_pairs;
        triangle_pair_contacts(a, i, b, j, time_begin, time_end, out, counters.primitives,
                               window);
      }
    }
  }
  const auto outside = [&](const Contact& c) {
    return !(c.time >= window_begin && c.time < window_end);
  };
  out.erase(std::remove_if(out.begin() + long(first), out.end(), outside), out.end());
}

}  // namespace kinray
