// KineticBvh at a flightplan key: the pass over every node above a mesh's leaves (children first),
// at once (eager trees) or node by node as the nodes are read (lazy trees: wake).
// The motion is linear on the new segment, so a certificate "r is beyond q" that holds at both of
// its keys holds in between: one comparison of key positions per certificate (with a margin far
// above the rounding of the segment's polynomial, so the decision agrees with the certificate's
// own failure time), and only the sides it does not decide get a failure time and an event. The
// pass reads each node's realizers, its children's and its triangle's key positions once and
// counts locally: it costs a few bottom-up passes, the fallbacks (~19k of 1.2M node sides per key
// on wavy-sphere 100k) and the events between keys the rest.
#include <cstring>

#include "kinetic/tree/kinetic_bvh.h"

namespace kinray {

namespace {

/// Sides set in a 6-bit mask. std::popcount is a libgcc call on x86-64 without POPCNT (every
/// x86-64 is the target), 3.5% of the key pass.
constexpr std::array<uint8_t, 64> kSidesIn = [] {
  std::array<uint8_t, 64> count{};
  for (unsigned mask = 0; mask < 64; ++mask) count[mask] = uint8_t(std::popcount(mask));
  return count;
}();

}  // namespace

void KineticBvh::refresh_mesh(uint32_t m) {
  uint64_t settled_total = 0;
  const bool moving = !m_meshes.still(m);
  for (uint32_t k = m_mesh_node_begin[m]; k < m_mesh_node_begin[m + 1]; ++k) {
    const uint32_t i = m_mesh_nodes[k];
    const BvhNode& n = m_topology.nodes[i];
    const uint8_t active =
        n.leaf() ? m_meshes.present(m) : uint8_t(m_node[n.left].active | m_node[n.right].active);
    if (active != m_node[i].active) ++m_presence_changes;
    m_node[i].active = active;
    if (m_config.lazy) {
      set_segment_box(i);
      sleep(i);
      continue;
    }
    settled_total += refresh_node(i, moving);
  }
  m_stats.certificates_computed += settled_total;
  m_stats.certificates_by_keys += settled_total;
}

uint32_t KineticBvh::refresh_node(uint32_t node, bool moving) {
  const uint8_t settled = moving ? settle_at_key(node) : 0;
  const uint8_t rest = uint8_t(m_node[node].sides & ~settled);
  if (rest != 0)
    for (int s = 0; s < 6; ++s)
      if (((rest >> s) & 1) != 0 && update_side(node, s)) ++m_stats.realizer_changes;
  return kSidesIn[settled & 63u];
}

void KineticBvh::sleep(uint32_t node) {
  NodeState& state = m_node[node];
  for (int s = 0; s < 6; ++s) {
    m_sim.queue().cancel(state.event[size_t(s)]);
    m_live_total -= state.live[size_t(s)];
    state.live[size_t(s)] = 0;
  }
  state.verified = 0;  // the keys it compared are no longer the segment's
  state.asleep = 1;
}

void KineticBvh::wake(uint32_t node) {
  if (m_node[node].asleep == 0) return;
  // The sleeping nodes of the subtree in preorder (an awake node's subtree is awake), then
  // computed in reverse: children before parents.
  m_wake_stack.assign(1, node);
  for (size_t k = 0; k < m_wake_stack.size(); ++k) {
    const BvhNode& n = m_topology.nodes[m_wake_stack[k]];
    if (n.leaf()) continue;
    if (m_node[n.left].asleep != 0) m_wake_stack.push_back(n.left);
    if (m_node[n.right].asleep != 0) m_wake_stack.push_back(n.right);
  }
  uint64_t settled_total = 0;
  for (size_t k = m_wake_stack.size(); k-- > 0;) {
    const uint32_t i = m_wake_stack[k];
    m_node[i].asleep = 0;
    const uint32_t m = m_node_mesh[i];
    // The key decision is sound at any time of the segment: beyond at both keys, beyond between.
    settled_total += refresh_node(i, m == kMixedMeshes || !m_meshes.still(m));
  }
  m_stats.nodes_woken += m_wake_stack.size();
  m_stats.certificates_computed += settled_total;
  m_stats.certificates_by_keys += settled_total;
  m_stats.certificates_live_max = std::max(m_stats.certificates_live_max, m_live_total);
}

void KineticBvh::set_segment_box(uint32_t node) {
  const BvhNode& n = m_topology.nodes[node];
  Aabb& box = m_segment_box[node];
  box = Aabb{};
  if (!m_node[node].active) return;
  if (n.leaf()) {
    for (uint32_t v : m_leaf_vertices[node]) {
      box.extend(m_meshes.key_start(v));
      box.extend(m_meshes.key_end(v));
    }
    return;
  }
  box = m_segment_box[n.left];
  box.extend(m_segment_box[n.right]);
}

void KineticBvh::settle_sides(uint32_t node, uint8_t sides, const std::array<uint8_t, 6>& live) {
  uint8_t* counted = m_node[node].live.data();
  std::array<EventHandle, 6>& events = m_node[node].event;
  // The common case at a key: every side settled as it was, no event pending (kNoEvent is all
  // ones, so the handles' AND is kNoEvent only when none is pending). Nothing to change.
  if (sides == 0x3F && std::memcmp(counted, live.data(), 6) == 0 &&
      (events[0] & events[1] & events[2] & events[3] & events[4] & events[5]) == kNoEvent)
    return;
  int64_t change = 0;
  for (int s = 0; s < 6; ++s) {
    if (((sides >> s) & 1) == 0) continue;
    change += int64_t(live[size_t(s)]) - int64_t(counted[s]);
    counted[s] = live[size_t(s)];
    m_sim.queue().cancel(events[size_t(s)]);
  }
  m_live_total = uint64_t(int64_t(m_live_total) + change);
}

uint8_t KineticBvh::settle_at_key(uint32_t node) {
  NodeState& state = m_node[node];
  const uint8_t tracked = state.sides;
  if (!state.active || tracked == 0) return 0;
  const BvhNode& n = m_topology.nodes[node];
  const std::array<uint32_t, 6>& realizer = state.realizer;
  const double margin = m_key_margin;
  // A verified side held by the margin at the key that starts this segment (NodeState::verified):
  // only its end key is compared.
  const uint8_t verified = state.verified;
  uint8_t settled = 0, by_margin = 0;
  std::array<uint8_t, 6> live{};
  if (n.leaf()) {
    const std::array<uint32_t, 3>& v = m_leaf_vertices[node];  // node order: no random load
    // The key positions, axis-major: p[key][axis][corner]; the start key's only when a side
    // needs it.
    double p[2][3][3];
    for (int c = 0; c < 3; ++c)
      for (int a = 0; a < 3; ++a) p[1][a][c] = m_meshes.key_end(v[size_t(c)])[a];
    if ((verified & tracked) != tracked)
      for (int c = 0; c < 3; ++c)
        for (int a = 0; a < 3; ++a) p[0][a][c] = m_meshes.key_start(v[size_t(c)])[a];
    for (int s = 0; s < 6; ++s) {
      const uint32_t r = realizer[size_t(s)];
      const int k = r == v[0] ? 0 : r == v[1] ? 1 : 2;
      if (((tracked >> s) & 1) == 0 || r != v[size_t(k)]) continue;  // untracked, just attached
      const int a = side_axis(s);
      const double sign = side_sign(s);
      const int j1 = k == 0 ? 1 : 0, j2 = k == 2 ? 1 : 2;  // the two other corners
      const auto beyond_at = [&](int key) {
        return sign * (p[key][a][k] - p[key][a][j1]) > margin &&
               sign * (p[key][a][k] - p[key][a][j2]) > margin;
      };
      if (!beyond_at(1) || (((verified >> s) & 1) == 0 && !beyond_at(0))) continue;
      live[size_t(s)] = 2;
      settled |= uint8_t(1u << s);
    }
    by_margin = settled;
  } else {
    // Below a node of one mesh every realizer and competitor is a vertex of the moving mesh being
    // refreshed, so beyond_at_both_keys needs no mesh test.
    const bool one_mesh = m_node_mesh[node] != kMixedMeshes;
    const std::array<uint32_t, 6>& left = m_node[n.left].realizer;
    const std::array<uint32_t, 6>& right = m_node[n.right].realizer;
    for (int s = 0; s < 6; ++s) {
      const uint32_t r = realizer[size_t(s)], l = left[size_t(s)], rr = right[size_t(s)];
      if (((tracked >> s) & 1) == 0 || r == kNoVertex) continue;
      if (l == kNoVertex || rr == kNoVertex || l == rr) {
        // One competitor only (an absent child, or both children realized by one shared vertex):
        // no certificate, the realizer is that vertex (update_side's answer, without its work).
        if (r != (l == kNoVertex ? rr : l)) continue;
      } else {
        if (r != l && r != rr) continue;
        const uint32_t q = r == l ? rr : l;
        const int axis = side_axis(s), sign = side_sign(s);
        if (one_mesh) {
          const auto beyond_at = [&](const Eigen::Vector3d& pr, const Eigen::Vector3d& pq) {
            return sign * (pr[axis] - pq[axis]) > margin;
          };
          if (!beyond_at(m_meshes.key_end(r), m_meshes.key_end(q)) ||
              (((verified >> s) & 1) == 0 &&
               !beyond_at(m_meshes.key_start(r), m_meshes.key_start(q))))
            continue;
          by_margin |= uint8_t(1u << s);
        } else if (!m_meshes.beyond_at_both_keys(r, q, axis, sign, margin)) {
          continue;
        }
        live[size_t(s)] = 1;
      }
      settled |= uint8_t(1u << s);
    }
  }
  state.verified = by_margin;
  const uint8_t open = uint8_t(tracked & ~settled);
  if (open != 0) settled |= settle_ties(node, open, live);
  if (settled != 0) settle_sides(node, settled, live);
  return settled;
}

uint8_t KineticBvh::settle_ties(uint32_t node, uint8_t open, std::array<uint8_t, 6>& live) const {
  const BvhNode& n = m_topology.nodes[node];
  const std::array<uint32_t, 6>& realizer = m_node[node].realizer;
  const double margin = m_key_margin;
  uint8_t settled = 0;
  for (int s = 0; s < 6; ++s) {
    const uint32_t r = realizer[size_t(s)];
    if (((open >> s) & 1) == 0 || r == kNoVertex) continue;
    const int axis = side_axis(s), sign = side_sign(s);
    // each competitor q: beyond at both keys, or tied at both keys with r the lower id
    const auto holds = [&](uint32_t q) {
      return q == r || m_meshes.beyond_at_both_keys(r, q, axis, sign, margin) ||
             (r < q && m_meshes.tied_at_both_keys(r, q, axis));
    };
    if (n.leaf()) {
      const std::array<uint32_t, 3>& v = m_leaf_vertices[node];
      if ((r != v[0] && r != v[1] && r != v[2]) || !holds(v[0]) || !holds(v[1]) || !holds(v[2]))
        continue;
      live[size_t(s)] = 2;
    } else {
      const uint32_t l = m_node[n.left].realizer[size_t(s)],
                     rr = m_node[n.right].realizer[size_t(s)];
      if (l == kNoVertex || rr == kNoVertex || l == rr || (r != l && r != rr) ||
          !holds(r == l ? rr : l))
        continue;
      live[size_t(s)] = 1;
    }
    settled |= uint8_t(1u << s);
  }
  return settled;
}

}  // namespace kinray
