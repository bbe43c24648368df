#include "kinetic/collision/kinetic_separation_list.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "kinetic/collision/exact_ccd.h"

namespace kinray {

namespace {
constexpr double kNever = std::numeric_limits<double>::infinity();
/// Heap order of the pending contacts: the earliest on top.
constexpr auto later = [](const Contact& x, const Contact& y) { return y < x; };
}  // namespace

KineticSeparationList::KineticSeparationList(KineticBvh& a, KineticBvh& b, double pad)
    : m_a(a), m_b(b), m_self(&a == &b), m_lazy(a.lazy() && b.lazy()), m_pad(pad), m_sim(a.now()) {
  KINRAY_CHECK_MSG(a.now() == b.now(), "kinetic separation list: trees at different times");
  m_head[0].assign(a.topology().nodes.size(), kNone);
  m_head[1].assign(b.topology().nodes.size(), kNone);
  m_stats.triangles = a.meshes().triangle_count() + (m_self ? 0 : b.meshes().triangle_count());
  for (int w = 0; m_lazy && w < 2; ++w) {  // nodes per subtree (children after parents)
    const std::vector<BvhNode>& nodes = tree(w).topology().nodes;
    std::vector<uint32_t>& size = m_subtree_nodes[size_t(w)];
    size.assign(nodes.size(), 1);
    for (uint32_t i = uint32_t(nodes.size()); i-- > 0;)
      if (!nodes[i].leaf()) size[i] += size[nodes[i].left] + size[nodes[i].right];
  }
  m_a.add_realizer_observer([this](uint32_t node, int side) {
    on_realizer_change(0, node, side);
    if (m_self) on_realizer_change(1, node, side);
  });
  if (!m_self)
    m_b.add_realizer_observer([this](uint32_t node, int side) { on_realizer_change(1, node, side); });
}

// ---- certificates ----------------------------------------------------------------------------

LinearCertificate KineticSeparationList::gap_certificate(const Record& r, int d) const {
  return gap_certificate(r.a, r.b, d, m_segment_begin);
}

LinearCertificate KineticSeparationList::gap_certificate(uint32_t a, uint32_t b, int d,
                                                         double origin) const {
  const int axis = d >> 1, lower = d & 1;  // lower: which box is below (its max against a min)
  const KineticBvh& lo = tree(lower);
  const KineticBvh& hi = tree(1 - lower);
  const uint32_t vlo = lo.realizer(lower == 0 ? a : b, side_of(axis, true));
  const uint32_t vhi = hi.realizer(lower == 0 ? b : a, side_of(axis, false));
  LinearCertificate c;
  c.origin = origin;
  c.end = m_segment_end;
  c.c0 = hi.meshes().coordinate(vhi, axis, origin) - lo.meshes().coordinate(vlo, axis, origin) -
         m_pad;
  c.c1 = hi.meshes().velocity(vhi, axis) - lo.meshes().velocity(vlo, axis);
  return c;
}

void KineticSeparationList::gap_certificates(const Record& r, Gaps& gaps) {
  // at[w][s], velocity[w][s]: side s of node w's box at the origin and its velocity, from its
  // realizer with gap_certificate's arithmetic, so the coefficients are the same doubles
  double at[2][6], velocity[2][6];
  for (int w = 0; w < 2; ++w) {
    const KineticBvh& t = tree(w);
    const TreeMeshes& meshes = t.meshes();
    const uint32_t n = node(r, w);
    for (int s = 0; s < 6; ++s) {
      const uint32_t v = t.realizer(n, s);
      at[w][s] = meshes.coordinate(v, side_axis(s), m_segment_begin);
      velocity[w][s] = meshes.velocity(v, side_axis(s));
    }
  }
  for (int d = 0; d < 6; ++d) {
    const int axis = d >> 1, lower = d & 1;
    const int max = side_of(axis, true), min = side_of(axis, false);
    LinearCertificate& c = gaps[size_t(d)];
    c.origin = m_segment_begin;
    c.end = m_segment_end;
    c.c0 = at[1 - lower][min] - at[lower][max] - m_pad;
    c.c1 = velocity[1 - lower][min] - velocity[lower][max];
  }
  m_stats.certificates_computed += 6;
}

int KineticSeparationList::find_witness(const Gaps& gaps, double& failure) const {
  const double now = m_sim.now();
  int best = -1;
  for (int d = 0; d < 6; ++d) {
    const LinearCertificate& c = gaps[size_t(d)];
    if (c.sign_after(now) <= 0) continue;
    const double f = c.failure_time(now);
    if (best < 0 || f > failure) {
      best = d;
      failure = f;
    }
  }
  return best;
}

int KineticSeparationList::apart_direction(uint32_t a, uint32_t b) const {
  // The trees' boxes at t are their realizers' a + b (t - o), within rounding (far below the pad)
  // of the key positions' hull: segment boxes apart by twice the pad keep every gap above the pad.
  const Aabb& x = m_a.segment_box(a);
  const Aabb& y = m_b.segment_box(b);
  const double margin = 2 * m_pad;
  for (int axis = 0; axis < 3; ++axis) {
    if (y.lo[axis] - x.hi[axis] > margin) return 2 * axis;  // a below b
    if (x.lo[axis] - y.hi[axis] > margin) return 2 * axis + 1;
  }
  return -1;
}

void KineticSeparationList::wake(const Record& r) {
  m_a.wake(r.a);
  m_b.wake(r.b);
}

// ---- records ---------------------------------------------------------------------------------

bool KineticSeparationList::pairable(uint32_t a, uint32_t b) const {
  if (!m_self) return true;
  const BvhNode& x = m_a.topology().nodes[a];
  const BvhNode& y = m_a.topology().nodes[b];
  if (!x.leaf() || !y.leaf()) return true;
  return a != b &&
         !triangles_adjacent(m_a.meshes().triangle(x.triangle), m_a.meshes().triangle(y.triangle));
}

KineticSeparationList::Children KineticSeparationList::children_of(uint32_t a, uint32_t b) const {
  Children out;
  const auto add = [&](uint32_t x, uint32_t y) {
    if (pairable(x, y)) out.pairs[size_t(out.count++)] = {x, y};
  };
  const BvhNode& x = m_a.topology().nodes[a];
  const BvhNode& y = m_b.topology().nodes[b];
  if (m_self && a == b) {
    if (x.leaf()) return out;  // a triangle against itself: no contact (a one-triangle mesh's root)
    add(x.left, x.left);
    add(x.left, x.right);
    add(x.right, x.right);
  } else if (x.leaf()) {
    if (!y.leaf()) {
      add(a, y.left);
      add(a, y.right);
    }
  } else if (y.leaf()) {
    add(x.left, b);
    add(x.right, b);
  } else {
    add(x.left, y.left);
    add(x.left, y.right);
    add(x.right, y.left);
    add(x.right, y.right);
  }
  return out;
}

uint32_t KineticSeparationList::create(uint32_t a, uint32_t b, uint32_t parent) {
  uint32_t id;
  if (!m_free.empty()) {
    id = m_free.back();
    m_free.pop_back();
  } else {
    id = uint32_t(m_records.size());
    m_records.emplace_back();
  }
  Record& r = m_records[id];
  r = Record{};
  r.a = a;
  r.b = b;
  r.parent = parent;
  r.alive = true;
  r.permanent = m_self && a == b;
  r.state = State::none;
  link(id);
  if (parent != kNone) {
    Record& p = m_records[parent];
    p.children[p.child_count++] = id;
  }
  return id;
}

void KineticSeparationList::link(uint32_t id) {
  Record& r = m_records[id];
  for (int w = 0; w < 2; ++w) {
    uint32_t& head = m_head[size_t(w)][node(r, w)];
    r.prev[size_t(w)] = kNone;
    r.next[size_t(w)] = head;
    if (head != kNone) m_records[head].prev[size_t(w)] = id;
    head = id;
  }
}

void KineticSeparationList::unlink(uint32_t id) {
  Record& r = m_records[id];
  for (int w = 0; w < 2; ++w) {
    const uint32_t prev = r.prev[size_t(w)], next = r.next[size_t(w)];
    if (prev != kNone)
      m_records[prev].next[size_t(w)] = next;
    else
      m_head[size_t(w)][node(r, w)] = next;
    if (next != kNone) m_records[next].prev[size_t(w)] = prev;
  }
}

void KineticSeparationList::destroy_children(uint32_t id) {
  Record& r = m_records[id];
  for (uint8_t k = 0; k < r.child_count; ++k) {
    const uint32_t child = m_records[id].children[k];
    destroy_children(child);
    set_state(child, State::none);
    schedule(child, kNever);
    unlink(child);
    m_records[child].alive = false;
    m_records[child].dirty = false;
    m_free.push_back(child);
  }
  m_records[id].child_count = 0;
}

void KineticSeparationList::set_state(uint32_t id, State state) {
  Record& r = m_records[id];
  auto count = [&](State s, int sign) {
    const uint64_t delta = uint64_t(int64_t(sign));
    if (s == State::separated || s == State::leaf || s == State::apart) m_stats.list_pairs += delta;
    if (s == State::leaf) m_stats.leaf_pairs += delta;
    if (s == State::apart) m_stats.apart_pairs += delta;
    if (s == State::expanded && !r.permanent) m_stats.watched_pairs += delta;
    m_stats.certificates_live += live_certificates(s, r.permanent) * delta;
  };
  count(r.state, -1);
  r.state = state;
  count(state, +1);
  m_stats.list_pairs_max = std::max(m_stats.list_pairs_max, m_stats.list_pairs);
  m_stats.certificates_live_max =
      std::max(m_stats.certificates_live_max, m_stats.certificates_live);
}

uint64_t KineticSeparationList::live_certificates(State state, bool permanent) {
  if (permanent) return 0;
  switch (state) {
    case State::separated:
      return 1;
    case State::leaf:
    case State::expanded:
      return 6;
    default:
      return 0;
  }
}

// ---- state changes ---------------------------------------------------------------------------

void KineticSeparationList::classify_new(uint32_t id) {
  if (m_records[id].permanent) {
    expand(id, nullptr);
    return;
  }
  if (m_lazy) {
    const int d = apart_direction(m_records[id].a, m_records[id].b);
    if (d >= 0) {
      m_records[id].witness = uint8_t(d);
      set_state(id, State::apart);
      return;
    }
    wake(m_records[id]);
  }
  Gaps gaps;
  gap_certificates(m_records[id], gaps);
  double failure = kNever;
  const int d = find_witness(gaps, failure);
  if (d < 0) {
    overlap(id, gaps);
    return;
  }
  m_records[id].witness = uint8_t(d);
  set_state(id, State::separated);
  schedule(id, failure);
}

void KineticSeparationList::overlap(uint32_t id, const Gaps& gaps) {
  const Record& r = m_records[id];
  if (m_a.topology().nodes[r.a].leaf() && m_b.topology().nodes[r.b].leaf()) {
    set_state(id, State::leaf);
    (void)watch(id, gaps);  // tests the pair up to its separation event
  } else {
    expand(id, &gaps);
  }
}

void KineticSeparationList::expand(uint32_t id, const Gaps* gaps) {
  set_state(id, State::expanded);
  for (const auto& [x, y] : children_of(m_records[id].a, m_records[id].b))
    classify_new(create(x, y, id));
  // the gaps are the record's own: its children's classification changes no realizer
  if (!m_records[id].permanent) (void)watch(id, *gaps);
}

void KineticSeparationList::separate(uint32_t id, int witness, double failure) {
  destroy_children(id);
  m_records[id].witness = uint8_t(witness);
  set_state(id, State::separated);
  schedule(id, failure);
}

KineticSeparationList::Outcome KineticSeparationList::watch(uint32_t id, const Gaps& gaps) {
  const double now = m_sim.now();
  // The six gaps share their origin and end, and one value per gap answers both questions: its
  // sign just after now (sign_after), and whether pad - gap_d, the exact negation (its value is
  // exactly -v), holds through the segment (linear_holds_through); only a gap that may turn
  // positive in the segment gets the full failure_time.
  const double s_now = now - gaps[0].origin, s_end = gaps[0].end - gaps[0].origin;
  double first = kNever;
  for (const LinearCertificate& c : gaps) {
    const double v = c.c0 + c.c1 * s_now;
    if (v > 0 || (v == 0 && c.c1 > 0)) {
      double failure = kNever;
      const int witness = find_witness(gaps, failure);  // before `failure` is read
      separate(id, witness, failure);
      return Outcome::separation;
    }
    const bool holds =
        (v < 0 || c.c1 < 0) && (c.c1 < 0 || (std::isfinite(s_end) && c.c0 + c.c1 * s_end < 0));
    if (!holds) first = std::min(first, c.negated().failure_time(now));  // pad - gap_d > 0
  }
  schedule(id, first);
  if (m_records[id].state == State::leaf) test_leaf(id);
  return Outcome::unchanged;
}

KineticSeparationList::Outcome KineticSeparationList::certify(uint32_t id) {
  Record& r = m_records[id];
  if (r.permanent || r.state == State::apart || r.state == State::unwatched)
    return Outcome::unchanged;
  if (m_lazy) {
    wake(r);
    r.dirty = false;  // certified now from the realizers the waking set
  }
  Gaps gaps;
  if (r.state != State::separated) {
    gap_certificates(r, gaps);
    return watch(id, gaps);
  }
  const double now = m_sim.now();
  const LinearCertificate c = gap_certificate(r, r.witness);
  ++m_stats.certificates_computed;
  if (c.sign_after(now) > 0) {
    schedule(id, c.failure_time(now));
    return Outcome::unchanged;
  }
  gap_certificates(r, gaps);
  double failure = kNever;
  const int d = find_witness(gaps, failure);
  if (d >= 0) {
    m_records[id].witness = uint8_t(d);
    schedule(id, failure);
    return Outcome::witness_change;
  }
  overlap(id, gaps);
  return Outcome::overlap;
}

void KineticSeparationList::count(Outcome outcome, Reason reason) {
  KslEventCounts& e = m_stats.events;
  switch (outcome) {
    case Outcome::overlap: ++e.overlap; break;
    case Outcome::separation: ++e.separation; break;
    case Outcome::witness_change: ++e.witness_change; break;
    case Outcome::unchanged:
      if (reason == Reason::event) ++e.rounding;
      if (reason == Reason::recertification) ++e.recertification;
      break;
  }
}

void KineticSeparationList::schedule(uint32_t id, double time) {
  if (!std::isfinite(time)) time = std::numeric_limits<double>::infinity();
  KINRAY_CHECK_MSG(time >= m_sim.now(), "kinetic separation list: certificate already broken");
  m_sim.queue().schedule(m_records[id].event, EventKey{time, 0, id, 0}, id);
}

// ---- time ------------------------------------------------------------------------------------

void KineticSeparationList::begin_segment(const MeshSweep& a, const MeshSweep& b,
                                          double time_begin, double time_end) {
  advance_to(time_begin);
  m_mesh_a = &a;
  m_mesh_b = &b;
  m_segment_begin = time_begin;
  m_segment_end = time_end;
  m_tested_until.clear();
  m_found.clear();
  ++m_stats.events.flightplan;
  if (m_root == kNone) {  // initialisation: the simultaneous traversal
    if (m_a.topology().nodes.empty() || m_b.topology().nodes.empty()) return;
    m_root = create(0, 0, kNone);
    if (m_lazy)
      recertify_at_key(m_root);
    else
      classify_new(m_root);
  } else if (m_lazy) {
    recertify_at_key(m_root);
  } else {
    for (uint32_t id = 0; id < m_records.size(); ++id)
      if (m_records[id].alive) count(certify(id), Reason::flightplan);  // tests listed leaves
  }
  if (m_lazy) recertify_dirty();  // pairs whose nodes a wake changed
}

void KineticSeparationList::recertify_at_key(uint32_t id) {
  if (!m_records[id].permanent) {
    const int d = apart_direction(m_records[id].a, m_records[id].b);
    if (d >= 0) {
      destroy_children(id);
      m_records[id].witness = uint8_t(d);
      set_state(id, State::apart);
      schedule(id, kNever);
      return;
    }
  }
  State state = m_records[id].state;
  if (state != State::expanded && state != State::unwatched && !m_records[id].permanent &&
      sleeping_nodes(m_records[id]) > kWakeLimit) {
    // Certifying the pair would wake more than kWakeLimit nodes: visit its children pairs instead,
    // which near a passage wake far fewer (the segment boxes set most of them apart).
    set_state(id, State::unwatched);
    schedule(id, kNever);
    ++m_stats.opened_at_keys;
    for (const auto& [x, y] : children_of(m_records[id].a, m_records[id].b)) create(x, y, id);
    state = State::unwatched;
  }
  switch (state) {
    case State::expanded:
    case State::unwatched: {
      const std::array<uint32_t, 4> children = m_records[id].children;
      const uint8_t child_count = m_records[id].child_count;
      for (uint8_t k = 0; k < child_count; ++k) recertify_at_key(children[k]);
      if (m_records[id].permanent) return;
      const Record& r = m_records[id];
      if (m_a.awake(r.a) && m_b.awake(r.b)) {
        set_state(id, State::expanded);
        count(certify(id), Reason::flightplan);  // watched: may separate
      } else {
        set_state(id, State::unwatched);
        schedule(id, kNever);
      }
      return;
    }
    case State::none:   // new (the root at the first key)
    case State::apart:  // no longer apart: certified from its (woken) realizers
      set_state(id, State::none);
      classify_new(id);
      return;
    default:
      count(certify(id), Reason::flightplan);  // tests listed leaves
  }
}

uint64_t KineticSeparationList::sleeping_nodes(const Record& r) const {
  return (m_a.awake(r.a) ? 0 : m_subtree_nodes[0][r.a]) +
         (m_b.awake(r.b) ? 0 : m_subtree_nodes[1][r.b]);
}

void KineticSeparationList::advance_to(double t) {
  do {
    m_sim.advance_to(t, [this](const EventKey&, uint64_t payload) {
      const auto id = uint32_t(payload);
      m_records[id].event = kNoEvent;
      count(certify(id), Reason::event);
    });
    recertify_dirty();
  } while (std::isfinite(t) && m_sim.next_event_time() <= t);
}

bool KineticSeparationList::relevant(const Record& r, int which, int side) const {
  if (r.permanent || r.state == State::none || r.state == State::apart ||
      r.state == State::unwatched)
    return false;
  if (r.state != State::separated) return true;
  const int axis = r.witness >> 1, lower = r.witness & 1;
  if (side_axis(side) != axis) return false;
  return side == side_of(axis, which == lower);  // the lower box's max, the upper box's min
}

void KineticSeparationList::on_realizer_change(int which, uint32_t node, int side) {
  for (uint32_t id = m_head[size_t(which)][node]; id != kNone;
       id = m_records[id].next[size_t(which)]) {
    Record& r = m_records[id];
    if (r.dirty || !relevant(r, which, side)) continue;
    r.dirty = true;
    m_dirty.push_back(id);
  }
}

void KineticSeparationList::recertify_dirty() {
  for (size_t k = 0; k < m_dirty.size(); ++k) {
    Record& r = m_records[m_dirty[k]];
    if (!r.alive || !r.dirty) continue;
    r.dirty = false;
    count(certify(m_dirty[k]), Reason::recertification);
  }
  m_dirty.clear();
}

// ---- contacts --------------------------------------------------------------------------------

uint64_t KineticSeparationList::triangle_pair(const Record& r) const {
  uint32_t ta = m_a.topology().nodes[r.a].triangle, tb = m_b.topology().nodes[r.b].triangle;
  if (m_self && tb < ta) std::swap(ta, tb);  // brute force's order: i < j
  return uint64_t(ta) << 32 | tb;
}

double KineticSeparationList::episode_end(const Record& r) const {
  if (r.event == kNoEvent) return m_segment_end;
  return std::min(m_sim.queue().key(r.event).time, m_segment_end);
}

void KineticSeparationList::test_leaf(uint32_t id) {
  Record& r = m_records[id];
  const uint64_t pair = triangle_pair(r);
  const double end = episode_end(r);
  const auto [until, first_test] = m_tested_until.try_emplace(pair, end);
  if (!first_test && *until >= end) return;
  const double begin = first_test ? m_sim.now() : std::max(m_sim.now(), *until);
  *until = end;
  // A wider window only meets contacts some window finds anyway: m_found drops the repeats.
  const LocalWindow window = local_window(m_segment_begin, m_segment_end, begin, end);
  ++m_stats.leaf_tests;
  ++m_counters.triangle_pairs;
  const uint32_t ta = uint32_t(pair >> 32), tb = uint32_t(pair);
  if (r.owned == kOwnersUnknown) r.owned = tested_primitives(*m_mesh_a, ta, *m_mesh_b, tb);
  const size_t first = m_pending.size();
  triangle_pair_contacts(*m_mesh_a, ta, *m_mesh_b, tb, m_segment_begin, m_segment_end, m_pending,
                         m_counters.primitives, window, r.owned);
  size_t kept = first;
  for (size_t k = first; k < m_pending.size(); ++k) {
    if (!m_found.insert(m_pending[k]).second) continue;  // found in an earlier window
    m_pending[kept] = m_pending[k];
    std::push_heap(m_pending.begin(), m_pending.begin() + long(++kept), later);
  }
  m_pending.resize(kept);
}

void KineticSeparationList::release_contacts(double t, std::vector<Contact>& out) {
  const double margin =
      4 * (kContactTimeEarliness * (m_segment_end - m_segment_begin) +
           std::numeric_limits<double>::epsilon() * std::max(std::fabs(t), std::fabs(m_segment_end)));
  const double threshold = std::isfinite(t) ? t - margin : t;
  while (!m_pending.empty() && m_pending.front().time <= threshold) {
    std::pop_heap(m_pending.begin(), m_pending.end(), later);
    const Contact c = m_pending.back();
    m_pending.pop_back();
    if (m_released_any && c == m_last_released) continue;  // met from another triangle pair
    m_released_any = true;
    m_last_released = c;
    out.push_back(c);
  }
}

KslStats KineticSeparationList::stats() const {
  return m_stats;
}

}  // namespace kinray
