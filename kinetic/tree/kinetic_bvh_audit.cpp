// KineticBvh::audit: the tree against a recomputation from its leaves (docs/design.md, "The
// audit": "every box equals the box recomputed from its leaves at a time strictly between events").
#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "kinetic/core/audit_failure.h"
#include "kinetic/tree/kinetic_bvh.h"

namespace kinray {
namespace {

/// Throws KineticAuditFailure naming the time, the place (a node and side, or the tree) and what
/// does not hold, as the grid's and the separation list's audits do.
[[noreturn]] void fail(double t, const std::string& where, const char* what) {
  std::ostringstream message;
  message.precision(17);
  message << "kinetic tree audit at t = " << t << ", " << where << ": " << what;
  throw KineticAuditFailure(message.str());
}

std::string node_side(uint32_t node, int side) {
  return "node " + std::to_string(node) + (side >= 0 ? " side " + std::to_string(side) : "");
}

}  // namespace

void KineticBvh::audit() const {
  m_sim.queue().audit();
  const double now = m_sim.now();
  const double next = m_sim.next_event_time();
  // Strictly between the last event handled (at or before now) and the next one.
  const double t = std::isfinite(next) ? now + 0.5 * (next - now) : now + 1.0;
  if (!(t > now && t < next)) return;  // the next event is one ulp away: nothing in between
  // extreme[i][s]: side s of node i recomputed from its leaves.
  const size_t nodes = m_topology.nodes.size();
  std::vector<std::array<AuditExtreme, 6>> extreme(nodes);
  for (uint32_t i = uint32_t(nodes); i-- > 0;) audit_node(i, t, extreme);
  if (live_certificates() != m_live_total) fail(t, "the tree", "live certificates miscounted");
  for (uint32_t m = 0; m < m_meshes.mesh_count(); ++m) {
    const double change = m_meshes.next_change(m, now);
    if (!(m_mesh_event[m] == kNoEvent ? !std::isfinite(change)
                                      : m_sim.queue().key(m_mesh_event[m]).time == change))
      fail(t, "mesh " + std::to_string(m),
           "its next key, appearance or disappearance is not scheduled");
  }
}

void KineticBvh::audit_node(uint32_t i, double t,
                            std::vector<std::array<AuditExtreme, 6>>& extreme) const {
  const BvhNode& n = m_topology.nodes[i];
  const bool present = n.leaf() ? m_meshes.present(m_meshes.mesh_of_triangle(n.triangle))
                                : (m_node[n.left].active | m_node[n.right].active) != 0;
  int side = -1;  // the side being checked, for the report
  const auto require = [&](bool holds, const char* what) {
    if (!holds) fail(t, node_side(i, side), what);
  };
  require(present == (m_node[i].active != 0), "wrong presence of a node");
  const bool asleep = m_node[i].asleep != 0;
  require(!asleep || m_config.lazy, "a node of an eager tree is asleep");
  require(asleep || n.leaf() || (m_node[n.left].asleep == 0 && m_node[n.right].asleep == 0),
          "an awake node has a sleeping child");
  if (m_config.lazy) {
    // The segment box holds every key position of the node's leaves on the current segments.
    Aabb keys;
    if (present && n.leaf()) {
      for (uint32_t v : m_meshes.triangle(n.triangle)) {
        keys.extend(m_meshes.key_start(v));
        keys.extend(m_meshes.key_end(v));
      }
    } else if (present) {
      keys = m_segment_box[n.left];
      keys.extend(m_segment_box[n.right]);
    }
    require(keys.lo == m_segment_box[i].lo && keys.hi == m_segment_box[i].hi,
            "a segment box differs from its leaves' key positions");
  }
  // Two coordinates a + b (t - o) of vertices whose exact motions cross within the rounding of
  // that evaluation (about 2 eps scale each: |a| and |b (t - o)| are at most about 2 scale) can
  // come out in the other order: the tree orders vertices by its certificates, c0 + c1 (t - o)
  // with c0 = a_r - a_q and c1 = b_r - b_q exact, not by rounded coordinates
  // (docs/kinetic_trees.md, "Audit").
  const double rounding = 8 * std::numeric_limits<double>::epsilon() * m_meshes.scale();
  for (int s = 0; s < 6; ++s) {
    side = s;
    const int axis = side_axis(s), sign = side_sign(s);
    // The winner just after t, as update_side compares: beyond, or tied with the lower id.
    const auto winner = [&](uint32_t p, uint32_t q) {
      if (p == kNoVertex) return q;
      if (q == kNoVertex || p == q) return p;
      return m_meshes.beats(p, q, axis, sign, t) ? p : q;
    };
    AuditExtreme e;
    if (present && n.leaf()) {
      const auto& v = m_meshes.triangle(n.triangle);
      e.vertex = winner(winner(v[0], v[1]), v[2]);
      for (uint32_t q : v) e.largest = std::max(e.largest, sign * m_meshes.coordinate(q, axis, t));
    } else if (present) {
      const AuditExtreme &l = extreme[n.left][size_t(s)], &rr = extreme[n.right][size_t(s)];
      e = {winner(l.vertex, rr.vertex), std::max(l.largest, rr.largest)};
    }
    extreme[i][size_t(s)] = e;
    const uint32_t r = m_node[i].realizer[size_t(s)];
    const EventHandle h = m_node[i].event[size_t(s)];
    const bool verified = ((m_node[i].verified >> s) & 1) != 0;
    if (asleep) {
      require(h == kNoEvent && !verified && m_node[i].live[size_t(s)] == 0,
              "a sleeping side has a certificate");
      continue;
    }
    if (((m_node[i].sides >> s) & 1) == 0 || !present) {
      require(r == kNoVertex && h == kNoEvent && !verified, "an untracked side has a realizer");
      continue;
    }
    require(r == e.vertex, "a side differs from the extreme of its leaves");
    // Its coordinate against the largest of the leaves' vertices, which may be another vertex's
    // only within the rounding of the two coordinates.
    require(e.largest - sign * m_meshes.coordinate(r, axis, t) <= rounding,
            "a side's coordinate is below its leaves' extreme");
    // The certificates: the realizer is beyond its competitors, and the earliest failure among
    // them is the scheduled event (none scheduled: none fails within the segments).
    double failure = kInfinityTime;
    auto check = [&](uint32_t q) {
      if (q == kNoVertex || q == r) return;
      const LinearCertificate c = m_meshes.beyond(r, q, axis, sign);
      require(c.sign_after(t) >= 0, "a certificate does not hold");
      failure = std::min(failure, c.failure_time(m_sim.now()));
    };
    // A verified side (the key pass compares it at the segment's end key only) holds by the
    // margin at both keys of the current segment against each competitor.
    bool by_margin = m_node_mesh[i] != kMixedMeshes;
    auto check_key = [&](uint32_t q) {
      by_margin = by_margin && (!verified || q == kNoVertex || q == r ||
                                m_meshes.beyond_at_both_keys(r, q, axis, sign, m_key_margin));
    };
    if (n.leaf()) {
      for (uint32_t q : m_meshes.triangle(n.triangle)) {
        check(q);
        check_key(q);
      }
    } else {
      for (const uint32_t q :
           {m_node[n.left].realizer[size_t(s)], m_node[n.right].realizer[size_t(s)]}) {
        check(q);
        check_key(q);
      }
    }
    require(!verified || by_margin, "a verified side does not hold by the margin at both keys");
    if (h == kNoEvent) {
      require(!std::isfinite(failure), "a failing certificate has no event");
    } else {
      const double scheduled = m_sim.queue().key(h).time;
      require(std::isfinite(failure) &&
                  std::fabs(failure - scheduled) <= 1e-9 * (1 + std::fabs(scheduled)),
              "an event is not at its certificate's failure time");
    }
  }
}

}  // namespace kinray
