#include "kinetic/collision/kinetic_contact_finder.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace kinray {

double KineticContactFinder::contact_pad(std::span<const FlightplanMesh> meshes, double t_end) {
  double scale = 0, speed = 0, time = std::isfinite(t_end) ? std::fabs(t_end) : 0;
  for (const FlightplanMesh& m : meshes) {
    for (const Eigen::Vector3d& p : m.positions) scale = std::max(scale, p.cwiseAbs().maxCoeff());
    for (size_t k = 0; k < m.key_count(); ++k) {
      time = std::max(time, std::fabs(m.key_times[k]));
      if (k == 0) continue;
      const double dt = m.key_times[k] - m.key_times[k - 1];
      for (uint32_t v = 0; v < m.vertex_count; ++v)
        speed = std::max(speed,
                         (m.key_position(k, v) - m.key_position(k - 1, v)).cwiseAbs().maxCoeff() / dt);
    }
  }
  return 1e-12 * scale + 64 * std::numeric_limits<double>::epsilon() * time * speed;
}

KineticContactFinder::KineticContactFinder(std::vector<FlightplanMesh> meshes,
                                           std::vector<std::pair<uint32_t, uint32_t>> pairs,
                                           double t, bool audit, bool lazy_trees)
    : m_pairs(std::move(pairs)), m_audit(audit) {
  m_pad = contact_pad(meshes, t);
  for (FlightplanMesh& mesh : meshes) {
    mesh.appear = -std::numeric_limits<double>::infinity();
    mesh.disappear = std::numeric_limits<double>::infinity();
    m_trees.push_back(
        std::make_unique<KineticBvh>(std::vector<FlightplanMesh>{mesh}, t,
                                     KineticBvh::Config{TreeShape::aabb, audit, lazy_trees}));
  }
  for (const auto& [i, j] : m_pairs)
    m_lists.push_back(std::make_unique<KineticSeparationList>(*m_trees[i], *m_trees[j], m_pad));
}

void KineticContactFinder::step_to(double t) {
  for (;;) {
    double next = t;
    for (const auto& tree : m_trees) next = std::min(next, tree->next_event_time());
    for (const auto& list : m_lists) next = std::min(next, list->next_event_time());
    for (const auto& tree : m_trees) tree->advance_to(next);
    for (const auto& list : m_lists) list->advance_to(next);
    if (next >= t) return;
  }
}

void KineticContactFinder::begin_segment(std::span<const MeshSweep> segments, double begin,
                                         double end) {
  step_to(begin);
  m_segment_end = end;
  for (size_t k = 0; k < m_lists.size(); ++k)
    m_lists[k]->begin_segment(segments[m_pairs[k].first], segments[m_pairs[k].second], begin, end);
  if (m_audit) audit();
}

void KineticContactFinder::advance_to(double t, std::vector<Contact>& out) {
  step_to(t);
  if (m_audit) audit();
  m_merge.clear();
  for (const auto& list : m_lists) list->release_contacts(t, m_merge);
  std::sort(m_merge.begin(), m_merge.end());
  out.insert(out.end(), m_merge.begin(), m_merge.end());
}

void KineticContactFinder::finish(std::vector<Contact>& out) {
  m_merge.clear();
  for (const auto& list : m_lists)
    list->release_contacts(std::numeric_limits<double>::infinity(), m_merge);
  std::sort(m_merge.begin(), m_merge.end());
  out.insert(out.end(), m_merge.begin(), m_merge.end());
}

void KineticContactFinder::audit() const {
  if (m_lists.empty()) return;
  const double now = m_lists.front()->now();
  double next = m_segment_end;
  for (const auto& tree : m_trees) next = std::min(next, tree->next_event_time());
  for (const auto& list : m_lists) next = std::min(next, list->next_event_time());
  const double t = now + 0.5 * (next - now);
  if (!(t > now && t < next)) return;  // nothing strictly in between
  for (const auto& list : m_lists) list->audit(t);
}

KslStats KineticContactFinder::stats() const {
  KslStats s;
  for (const auto& list : m_lists) s += list->stats();
  return s;
}

TreeStats KineticContactFinder::tree_stats() const {
  TreeStats s;
  for (const auto& tree : m_trees) {
    const TreeStats t = tree->stats();
    s.events.leaf += t.events.leaf;
    s.events.tree += t.events.tree;
    s.events.flightplan += t.events.flightplan;
    s.events_external += t.events_external;
    s.events_internal += t.events_internal;
    s.realizer_changes += t.realizer_changes;
    s.nodes_woken += t.nodes_woken;
    s.certificates_computed += t.certificates_computed;
    s.certificates_live += t.certificates_live;
    s.certificates_live_max += t.certificates_live_max;
    s.nodes += t.nodes;
    s.triangles += t.triangles;
  }
  return s;
}

ContactCounters KineticContactFinder::counters() const {
  ContactCounters c;
  for (const auto& list : m_lists) c += list->counters();
  return c;
}

}  // namespace kinray
