// KineticSeparationList::audit: the list against a fresh simultaneous traversal of the two trees
// (docs/design.md, "The audit": "the list equals a fresh traversal's front at a time strictly
// between events"), and every record's certificates against a recomputation from its current
// realizers.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "kinetic/collision/kinetic_separation_list.h"
#include "kinetic/core/audit_failure.h"

namespace kinray {

namespace {

[[noreturn]] void fail(const std::string& what, double t, uint32_t a, uint32_t b) {
  std::ostringstream message;
  message.precision(17);
  message << "kinetic separation list audit at t = " << t << ", node pair (" << a << ", " << b
          << "): " << what;
  throw KineticAuditFailure(message.str());
}

bool near(double x, double y) {
  return x == y || std::fabs(x - y) <= 1e-9 * (1 + std::fabs(y));
}

}  // namespace

std::vector<KslPair> KineticSeparationList::front() const {
  std::vector<KslPair> out;
  for (const Record& r : m_records)
    if (r.alive &&
        (r.state == State::separated || r.state == State::leaf || r.state == State::apart))
      out.push_back({r.a, r.b, r.state == State::leaf});
  std::sort(out.begin(), out.end());
  return out;
}

double KineticSeparationList::side_at(int which, uint32_t node, int s, double t) const {
  const KineticBvh& bvh = tree(which);
  const TreeMeshes& meshes = bvh.meshes();
  const int axis = side_axis(s), sign = side_sign(s);
  if (bvh.awake(node)) return meshes.coordinate(bvh.realizer(node, s), axis, t);
  double extreme = -sign * std::numeric_limits<double>::infinity();
  std::vector<uint32_t> stack{node};
  while (!stack.empty()) {
    const BvhNode& n = bvh.topology().nodes[stack.back()];
    stack.pop_back();
    if (!n.leaf()) {
      stack.push_back(n.left);
      stack.push_back(n.right);
      continue;
    }
    for (uint32_t v : meshes.triangle(n.triangle)) {
      const double x = meshes.coordinate(v, axis, t);
      extreme = sign > 0 ? std::max(extreme, x) : std::min(extreme, x);
    }
  }
  return extreme;
}

bool KineticSeparationList::separated_at(uint32_t a, uint32_t b, double t) const {
  // gap_certificate(a, b, d, t).c0 > 0, with the same arithmetic, from side_at
  for (int d = 0; d < 6; ++d) {
    const int axis = d >> 1, lower = d & 1;
    const uint32_t below = lower == 0 ? a : b, above = lower == 0 ? b : a;
    if (side_at(1 - lower, above, side_of(axis, false), t) -
            side_at(lower, below, side_of(axis, true), t) - m_pad >
        0)
      return true;
  }
  return false;
}

bool KineticSeparationList::has_record(uint32_t a, uint32_t b, State state) const {
  for (uint32_t id = m_head[0][a]; id != kNone; id = m_records[id].next[0])
    if (m_records[id].b == b && m_records[id].state == state) return true;
  return false;
}

void KineticSeparationList::traverse(uint32_t a, uint32_t b, double t,
                                     std::vector<KslPair>& out) const {
  // An unwatched pair (lazy trees) stays expanded to its key, separated or not.
  if (!(m_self && a == b) && !has_record(a, b, State::unwatched)) {
    if (separated_at(a, b, t)) {
      out.push_back({a, b, false});
      return;
    }
    if (m_a.topology().nodes[a].leaf() && m_b.topology().nodes[b].leaf()) {
      out.push_back({a, b, true});
      return;
    }
  }
  for (const auto& [x, y] : children_of(a, b)) traverse(x, y, t, out);
}

std::vector<KslPair> KineticSeparationList::traversal_front(double t) const {
  std::vector<KslPair> out;
  if (m_root != kNone) traverse(0, 0, t, out);
  std::sort(out.begin(), out.end());
  return out;
}

void KineticSeparationList::audit_record(uint32_t id, double t) const {
  const Record& r = m_records[id];
  const double now = m_sim.now();
  if (r.dirty) fail("a realizer change was not recertified", t, r.a, r.b);
  for (uint8_t k = 0; k < r.child_count; ++k)
    if (m_records[r.children[k]].parent != id || !m_records[r.children[k]].alive)
      fail("a child record does not name its parent", t, r.a, r.b);
  if (r.state != State::expanded && r.state != State::unwatched && r.child_count != 0)
    fail("a listed pair has children", t, r.a, r.b);
  const bool certified = !r.permanent && r.state != State::apart && r.state != State::unwatched;
  if (certified && !(m_a.awake(r.a) && m_b.awake(r.b)))
    fail("a certified pair reads a sleeping node", t, r.a, r.b);
  double failure = kInfinityTime;
  if (r.state == State::apart) {
    if (apart_direction(r.a, r.b) < 0) fail("an apart pair's segment boxes meet", t, r.a, r.b);
    if (!separated_at(r.a, r.b, t)) fail("an apart pair is not separated", t, r.a, r.b);
  } else if (r.state == State::unwatched) {
    // no certificate: kept expanded to the next key
  } else if (r.permanent) {
    if (r.state != State::expanded) fail("a node with itself is not expanded", t, r.a, r.b);
  } else if (r.state == State::separated) {
    const LinearCertificate c = gap_certificate(r, r.witness);
    if (c.sign_after(t) <= 0) fail("the separating witness does not hold", t, r.a, r.b);
    failure = c.failure_time(now);
  } else {
    for (int d = 0; d < 6; ++d) {
      const LinearCertificate c = gap_certificate(r, d);
      if (c.sign_after(t) > 0) fail("a watched overlapping pair is separated", t, r.a, r.b);
      failure = std::min(failure, c.negated().failure_time(now));
    }
  }
  const bool scheduled = r.event != kNoEvent;
  if (scheduled != std::isfinite(failure) ||
      (scheduled && !near(m_sim.queue().key(r.event).time, failure)))
    fail("the event is not at the certificate's failure time", t, r.a, r.b);
  if (r.state == State::leaf) {
    const double* until = m_tested_until.find(triangle_pair(r));
    if (until == nullptr)
      fail("a listed triangle pair was not tested on this segment", t, r.a, r.b);
    if (*until < episode_end(r) || *until < t)
      fail("a listed triangle pair was not tested up to its separation event", t, r.a, r.b);
  }
}

void KineticSeparationList::audit(double t) const {
  m_sim.queue().audit();
  if (!(t > m_sim.now() && t < m_sim.next_event_time() && t <= m_segment_end))
    fail("the audit time is not strictly between events", t, 0, 0);
  uint64_t memberships = 0, alive = 0, live = 0;
  for (int w = 0; w < 2; ++w)
    for (uint32_t n = 0; n < m_head[size_t(w)].size(); ++n)
      for (uint32_t id = m_head[size_t(w)][n]; id != kNone; id = m_records[id].next[size_t(w)]) {
        if (!m_records[id].alive || node(m_records[id], w) != n)
          fail("a node's record list is wrong", t, n, id);
        ++memberships;
      }
  for (uint32_t id = 0; id < m_records.size(); ++id) {
    const Record& r = m_records[id];
    if (!r.alive) continue;
    ++alive;
    live += live_certificates(r.state, r.permanent);
    audit_record(id, t);
  }
  if (memberships != 2 * alive) fail("a record is missing from its nodes' lists", t, 0, 0);
  if (live != m_stats.certificates_live) fail("live certificates miscounted", t, 0, 0);
  const std::vector<KslPair> listed = front(), fresh = traversal_front(t);
  if (listed.size() != m_stats.list_pairs) fail("the list's size is miscounted", t, 0, 0);
  if (listed != fresh) {
    size_t k = 0;
    while (k < listed.size() && k < fresh.size() && listed[k] == fresh[k]) ++k;
    const KslPair p = k < listed.size() ? listed[k] : fresh[k];
    fail("the list differs from a fresh traversal's front (" + std::to_string(listed.size()) +
             " listed, " + std::to_string(fresh.size()) + " in the front)",
         t, p.a, p.b);
  }
}

}  // namespace kinray
