#include "kinetic/tree/kinetic_bvh.h"

#include <algorithm>
#include <bit>
#include <chrono>
#include <cmath>

#include "util/check.h"

namespace kinray {

namespace {

/// The sides each node tracks: all six in the AABB tree; in the BoxTree the sides its ancestors'
/// split planes need (a left child's max and a right child's min along the parent's axis, which
/// are extremes of every node below, so the need passes down).
std::vector<uint8_t> tracked_sides(const BvhTopology& topology, TreeShape shape) {
  std::vector<uint8_t> sides(topology.nodes.size(), shape == TreeShape::aabb ? 0x3F : 0);
  if (shape == TreeShape::aabb) return sides;
  for (uint32_t i = 0; i < topology.nodes.size(); ++i) {
    const BvhNode& n = topology.nodes[i];
    if (n.leaf()) continue;
    sides[n.left] |= uint8_t(sides[i] | (1u << side_of(n.axis, true)));
    sides[n.right] |= uint8_t(sides[i] | (1u << side_of(n.axis, false)));
  }
  return sides;
}

}  // namespace

KineticBvh::KineticBvh(std::vector<FlightplanMesh> meshes, double t, const Config& config)
    : m_config(config), m_meshes(std::move(meshes), t), m_sim(t) {
  const uint32_t triangles = m_meshes.triangle_count();
  std::vector<Aabb> boxes(triangles);
  for (uint32_t tri = 0; tri < triangles; ++tri)
    for (uint32_t v : m_meshes.triangle(tri))
      boxes[tri].extend(Eigen::Vector3d(m_meshes.coordinate(v, 0, t), m_meshes.coordinate(v, 1, t),
                                        m_meshes.coordinate(v, 2, t)));
  m_topology = build_binned_sah(boxes);
  const size_t nodes = m_topology.nodes.size();
  m_node.resize(nodes);
  const std::vector<uint8_t> sides = tracked_sides(m_topology, config.shape);
  for (size_t i = 0; i < nodes; ++i) m_node[i].sides = sides[i];
  m_node_mesh.assign(nodes, kMixedMeshes);
  for (uint32_t i = uint32_t(nodes); i-- > 0;) {
    const BvhNode& n = m_topology.nodes[i];
    m_node_mesh[i] = n.leaf() ? m_meshes.mesh_of_triangle(n.triangle)
                     : m_node_mesh[n.left] == m_node_mesh[n.right] ? m_node_mesh[n.left]
                                                                   : kMixedMeshes;
  }
  m_leaf_vertices.assign(nodes, {kNoVertex, kNoVertex, kNoVertex});
  for (uint32_t i = 0; i < nodes; ++i)
    if (m_topology.nodes[i].leaf())
      m_leaf_vertices[i] = m_meshes.triangle(m_topology.nodes[i].triangle);
  m_key_margin = 1e-12 * m_meshes.scale();

  // Per mesh, the nodes above its leaves (descending, so children come before parents).
  const uint32_t mesh_count = m_meshes.mesh_count();
  std::vector<uint32_t> mark(nodes, kNoNode), leaf_of(triangles, kNoNode);
  for (uint32_t i = 0; i < nodes; ++i)
    if (m_topology.nodes[i].leaf()) leaf_of[m_topology.nodes[i].triangle] = i;
  m_mesh_node_begin.assign(mesh_count + 1, 0);
  for (uint32_t m = 0; m < mesh_count; ++m) {
    const size_t first = m_mesh_nodes.size();
    for (uint32_t tri = m_meshes.triangle_begin(m); tri < m_meshes.triangle_end(m); ++tri)
      for (uint32_t n = leaf_of[tri]; n != kNoNode && mark[n] != m;
           n = m_topology.nodes[n].parent) {
        mark[n] = m;
        m_mesh_nodes.push_back(n);
      }
    std::sort(m_mesh_nodes.begin() + long(first), m_mesh_nodes.end(), std::greater<>());
    m_mesh_node_begin[m + 1] = uint32_t(m_mesh_nodes.size());
  }

  if (config.lazy) m_segment_box.resize(nodes);
  for (uint32_t i = uint32_t(nodes); i-- > 0;) {
    const BvhNode& n = m_topology.nodes[i];
    m_node[i].active = n.leaf() ? m_meshes.present(m_meshes.mesh_of_triangle(n.triangle))
                                : uint8_t(m_node[n.left].active | m_node[n.right].active);
    if (config.lazy) {  // asleep from the start: the first reader wakes what it reads
      set_segment_box(i);
      m_node[i].asleep = 1;
      continue;
    }
    for (int s = 0; s < 6; ++s)
      if ((m_node[i].sides >> s) & 1) update_side(i, s);
  }
  m_mesh_event.assign(mesh_count, kNoEvent);
  for (uint32_t m = 0; m < mesh_count; ++m) schedule_mesh(m);
  m_stats.certificates_live_max = m_live_total;
  if (m_config.audit) audit();
}

bool KineticBvh::update_side(uint32_t node, int s) {
  ++m_stats.certificates_computed;
  const BvhNode& n = m_topology.nodes[node];
  const int axis = side_axis(s), sign = side_sign(s);
  const double now = m_sim.now();
  uint32_t& realizer = m_node[node].realizer[size_t(s)];
  const uint32_t before = realizer;
  double failure = kInfinityTime;
  uint8_t live = 0;
  // Each pair's comparison is built once: who wins just after now, and the winner's certificate.
  auto winner = [&](uint32_t p, uint32_t q, LinearCertificate& c) {
    c = m_meshes.beyond(p, q, axis, sign);
    const int sg = c.sign_after(now);
    if (sg > 0 || (sg == 0 && p < q)) return p;
    c = c.negated();
    return q;
  };
  if (!m_node[node].active) {
    realizer = kNoVertex;
  } else if (n.leaf()) {
    const auto& v = m_meshes.triangle(n.triangle);
    LinearCertificate c01, c2;
    const uint32_t w01 = winner(v[0], v[1], c01), l01 = w01 == v[0] ? v[1] : v[0];
    realizer = winner(w01, v[2], c2);  // c2: the realizer against the other of (w01, v2)
    const uint32_t against2 = realizer == w01 ? v[2] : w01;
    if (against2 != realizer) {
      failure = c2.failure_time(now);
      ++live;
    }
    if (l01 != realizer) {  // against the loser of (v0, v1): c01 unless v2 took over
      const LinearCertificate c =
          realizer == w01 ? c01 : m_meshes.beyond(realizer, l01, axis, sign);
      failure = std::min(failure, c.failure_time(now));
      ++live;
    }
  } else {
    const uint32_t l = m_node[n.left].realizer[size_t(s)], r = m_node[n.right].realizer[size_t(s)];
    if (l == kNoVertex || r == kNoVertex) {
      realizer = l == kNoVertex ? r : l;
    } else if (l == r) {
      realizer = l;
    } else {
      LinearCertificate c;
      realizer = winner(l, r, c);
      failure = c.failure_time(now);
      live = 1;
    }
  }
  // Recomputed: the key pass compares this side at both keys again, and a parent whose
  // competitor this realizer is, too.
  m_node[node].verified &= uint8_t(~(1u << s));
  if (realizer != before && n.parent != kNoNode) m_node[n.parent].verified &= uint8_t(~(1u << s));
  uint8_t& counted = m_node[node].live[size_t(s)];
  m_live_total += uint64_t(live) - uint64_t(counted);
  counted = live;
  schedule(node, s, failure);
  if (realizer == before) return false;
  for (const RealizerObserver& observer : m_observers) observer(node, s);
  return true;
}

void KineticBvh::schedule(uint32_t node, int s, double time) {
  if (!std::isfinite(time)) time = kInfinityTime;
  KINRAY_CHECK_MSG(time >= m_sim.now(), "kinetic tree: certificate already broken");
  const EventKey key{time, m_topology.nodes[node].leaf() ? kLeafKind : kTreeKind, node,
                     uint64_t(s)};
  m_sim.queue().schedule(m_node[node].event[size_t(s)], key, uint64_t(node) * 8 + uint64_t(s));
}

void KineticBvh::schedule_mesh(uint32_t m) {
  const double next = m_meshes.next_change(m, m_sim.now());
  m_sim.queue().schedule(m_mesh_event[m], EventKey{std::isfinite(next) ? next : kInfinityTime, kMeshKind, m, 0},
                         kMeshEvent | m);
}

void KineticBvh::advance_to(double t) {
  m_sim.advance_to(t, [this](const EventKey& key, uint64_t payload) { handle(key, payload); });
  if (m_config.audit) audit();
}

void KineticBvh::handle(const EventKey& key, uint64_t payload) {
  if ((payload & kMeshEvent) != 0) {
    m_mesh_event[uint32_t(payload)] = kNoEvent;
    handle_mesh(uint32_t(payload));
    return;
  }
  const auto node = uint32_t(payload >> 3);
  const int s = int(payload & 7);
  m_node[node].event[size_t(s)] = kNoEvent;
  ++(key.kind == kLeafKind ? m_stats.events.leaf : m_stats.events.tree);
  if (!update_side(node, s)) {  // a failure at the level of rounding: the same vertex still wins
    ++m_stats.events_internal;
    return;
  }
  ++m_stats.events_external;
  ++m_stats.realizer_changes;
  m_stats.certificates_live_max = std::max(m_stats.certificates_live_max, m_live_total);
  // Climb while the parents track this side and their realizers change; a parent whose realizer
  // stays has its certificate recomputed all the same (its other competitor changed).
  // A sleeping parent (lazy trees) is computed when it is woken.
  for (uint32_t p = m_topology.nodes[node].parent;
       p != kNoNode && ((m_node[p].sides >> s) & 1) != 0 && m_node[p].asleep == 0;
       p = m_topology.nodes[p].parent) {
    if (!update_side(p, s)) break;
    ++m_stats.realizer_changes;
  }
}

void KineticBvh::handle_mesh(uint32_t m) {
  const auto start = std::chrono::steady_clock::now();
  const double t = m_sim.now();
  const bool was_present = m_meshes.present(m);
  m_meshes.set_time(m, t);
  if (m_meshes.present(m) && !was_present)
    ++m_stats.events.insert;
  else if (!m_meshes.present(m) && was_present)
    ++m_stats.events.remove;
  else
    ++m_stats.events.flightplan;
  const uint64_t changes = m_stats.realizer_changes;
  refresh_mesh(m);
  m_stats.certificates_live_max = std::max(m_stats.certificates_live_max, m_live_total);
  ++(m_stats.realizer_changes != changes ? m_stats.events_external : m_stats.events_internal);
  schedule_mesh(m);
  m_mesh_event_seconds +=
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

uint64_t KineticBvh::live_certificates() const {
  uint64_t live = 0;
  for (uint32_t i = 0; i < m_topology.nodes.size(); ++i) {
    if (!m_node[i].active || m_node[i].asleep != 0) continue;
    const BvhNode& n = m_topology.nodes[i];
    for (int s = 0; s < 6; ++s) {
      if (((m_node[i].sides >> s) & 1) == 0) continue;
      if (n.leaf()) {
        for (uint32_t q : m_meshes.triangle(n.triangle)) live += q != m_node[i].realizer[size_t(s)];
      } else {
        const uint32_t l = m_node[n.left].realizer[size_t(s)],
                       r = m_node[n.right].realizer[size_t(s)];
        live += l != kNoVertex && r != kNoVertex && l != r;
      }
    }
  }
  return live;
}

TreeStats KineticBvh::stats() const {
  TreeStats s = m_stats;
  s.certificates_live = m_live_total;
  s.scheduled_events = m_sim.queue().size();
  s.nodes = m_topology.nodes.size();
  s.height = m_topology.height();
  s.node_sides = 0;
  for (const NodeState& node : m_node) s.node_sides += uint64_t(std::popcount(node.sides));
  s.triangles = m_meshes.triangle_count();
  s.triangles_present = 0;
  for (uint32_t m = 0; m < m_meshes.mesh_count(); ++m)
    if (m_meshes.present(m))
      s.triangles_present += m_meshes.triangle_end(m) - m_meshes.triangle_begin(m);
  for (EventHandle h : m_mesh_event) s.scheduled_events -= h != kNoEvent;
  return s;
}

size_t KineticBvh::memory_bytes() const {
  return m_topology.nodes.capacity() * sizeof(BvhNode) + m_node.capacity() * sizeof(NodeState) +
         m_node_mesh.capacity() * sizeof(uint32_t) +
         m_leaf_vertices.capacity() * sizeof(m_leaf_vertices[0]) +
         m_mesh_nodes.capacity() * sizeof(uint32_t) + m_sim.queue().memory_bytes() +
         m_segment_box.capacity() * sizeof(Aabb) +
         size_t(m_meshes.vertex_count()) * 2 * sizeof(Eigen::Vector3d) +
         size_t(m_meshes.triangle_count()) * 4 * sizeof(uint32_t);
}

}  // namespace kinray
