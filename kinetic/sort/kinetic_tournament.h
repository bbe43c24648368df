#pragma once
// Kinetic tournament tree: the front (minimum) only; an event touches O(log n) certificates
// (Basch, Guibas & Hershberger 1997; Agarwal et al., kinetic tournaments).

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <span>
#include <vector>

#include "kinetic/sort/id_index.h"
#include "kinetic/sort/kinetic_sort.h"
#include "kinetic/sort/sort_core.h"

namespace kinray {

template <KineticKeys Keys>
class KineticTournament {
 public:
  using keys_type = Keys;

  KineticTournament(const Keys& keys, EventQueue& queue, uint32_t owner,
                    const KineticSortConfig& config = {})
      : m_core(keys, queue, owner, config) {}
  KineticTournament(KineticTournament&&) noexcept = default;
  KineticTournament& operator=(KineticTournament&&) noexcept = default;
  KineticTournament(const KineticTournament&) = delete;
  KineticTournament& operator=(const KineticTournament&) = delete;

  /// O(log n) certificates (amortised: the tree doubles when full).
  void insert(uint32_t id, double now) {
    KINRAY_DCHECK(!contains(id));
    if (m_size == m_capacity) rebuild(m_capacity == 0 ? 1 : 2 * m_capacity, leaf_ids(), now);
    const uint32_t leaf = m_capacity + m_size;
    ++m_size;
    if (m_size > 1) ++m_core.stats().certificates_live;
    set_leaf(leaf, id);
    update_path(leaf, now);
    if (m_core.audit_on()) audit(now);
  }

  /// Inserts many objects at once: the tree is rebuilt bottom-up, O(n) certificates.
  void insert_all(std::span<const uint32_t> ids, double now) {
    std::vector<uint32_t> all = leaf_ids();
    all.insert(all.end(), ids.begin(), ids.end());
    if (m_size > 1) m_core.stats().certificates_live -= m_size - 1;
    if (all.size() > 1) m_core.stats().certificates_live += all.size() - 1;
    uint32_t capacity = 1;
    while (capacity < all.size()) capacity *= 2;
    rebuild(capacity, all, now);
    if (m_core.audit_on()) audit(now);
  }

  /// O(log n) certificates: the last leaf moves into the hole.
  void erase(uint32_t id, double now) {
    const uint32_t leaf = find_leaf(id);
    const uint32_t last = m_capacity + m_size - 1;
    if (m_index) m_index->erase(id);
    if (leaf != last) {
      set_leaf(leaf, m_nodes[last].winner);
      m_nodes[last].winner = kNone;
      --m_size;
      update_path(last, now);
      update_path(leaf, now);
    } else {
      m_nodes[last].winner = kNone;
      --m_size;
      update_path(last, now);
    }
    if (m_size > 0) --m_core.stats().certificates_live;
    if (m_capacity > 1 && m_size <= m_capacity / 4) rebuild(m_capacity / 2, leaf_ids(), now);
    if (m_core.audit_on()) audit(now);
  }

  /// The motion of id changed from now on: recompute the matches on its path.
  void replace_motion(uint32_t id, double now) {
    const uint32_t leaf = find_leaf(id);
    for (uint32_t k = leaf / 2; k >= 1; k /= 2) recompute(k, now);
    if (m_core.audit_on()) audit(now);
  }

  /// The motions of the members for which moved(id) holds changed from now on: every match with
  /// a moved member below it is recomputed once, children first, where replace_motion on each
  /// would recompute the matches their paths share once per member.
  template <class Moved>
  void replace_motions(Moved&& moved, double now) {
    if (m_size >= 2) {  // else no match (and m_capacity may be 0)
      std::vector<uint8_t> touched(m_capacity, 0);
      for (uint32_t i = 0; i < m_size; ++i)
        if (moved(m_nodes[m_capacity + i].winner)) touched[(m_capacity + i) / 2] = 1;
      for (uint32_t k = m_capacity - 1; k >= 1; --k) {
        if (touched[k] == 0) continue;
        recompute(k, now);
        touched[k / 2] = 1;
      }
    }
    if (m_core.audit_on()) audit(now);
  }

  void handle_event(uint64_t payload, double now) {
    const auto k = static_cast<uint32_t>(payload);
    KINRAY_CHECK(k >= 1 && k < m_capacity);
    m_nodes[k].event = kNoEvent;  // popped
    m_core.begin_event(now);
    const std::optional<uint32_t> old_front = front();
    KineticSortStats& st = m_core.stats();
    if (!recompute(k, now)) {
      ++st.events_renewal;
    } else {
      for (uint32_t p = k / 2; p >= 1; p /= 2)
        if (!recompute(p, now)) break;
      ++(front() != old_front ? st.events_external : st.events_internal);
    }
    if (m_core.audit_on()) audit(now);
  }

  [[nodiscard]] std::optional<uint32_t> front() const {
    if (m_size == 0) return std::nullopt;
    return m_nodes[1].winner;
  }
  [[nodiscard]] size_t size() const { return m_size; }
  [[nodiscard]] bool empty() const { return m_size == 0; }
  [[nodiscard]] bool contains(uint32_t id) const {
    if (m_index) return m_index->contains(id);
    for (uint32_t i = 0; i < m_size; ++i)
      if (m_nodes[m_capacity + i].winner == id) return true;
    return false;
  }
  /// f(id) for every object, in no particular order.
  template <class F>
  void for_each(F&& f) const {
    for (uint32_t i = 0; i < m_size; ++i) f(m_nodes[m_capacity + i].winner);
  }

  /// Every match recomputed at t: the winner is one of the two children's winners and beats the
  /// other just after t, or the match's event is pending at t.
  /// The first problem found, or nothing; never aborts, so the owner can add where it was found.
  [[nodiscard]] std::optional<std::string> audit_problem(double t) const {
    if (m_capacity == 0) return std::nullopt;
    for (uint32_t leaf = m_capacity; leaf < 2 * m_capacity; ++leaf)
      if ((leaf < m_capacity + m_size) != (m_nodes[leaf].winner != kNone))
        return "kinetic tournament: leaf " + std::to_string(leaf) + " does not match the size";
    for (uint32_t k = m_capacity - 1; k >= 1; --k) {
      const uint32_t l = m_nodes[2 * k].winner, r = m_nodes[2 * k + 1].winner;
      const Node& node = m_nodes[k];
      const std::string at = "kinetic tournament: match " + std::to_string(k);
      if (l == kNone || r == kNone) {
        if (!(node.winner == (l == kNone ? r : l) && node.event == kNoEvent))
          return at + " with one player has a wrong winner or an event";
        continue;
      }
      if (!(node.winner == l || node.winner == r)) return at + ": the winner is neither player";
      if (node.event != kNoEvent && m_core.queue().payload(node.event) != k)
        return at + ": its event belongs to another match";
      const uint32_t loser = node.winner == l ? r : l;
      if (auto problem = m_core.pair_problem(node.winner, loser, node.event, t)) return problem;
    }
    return std::nullopt;
  }
  /// Throws KineticAuditFailure with audit_problem(t), if any.
  void audit(double t) const {
    if (std::optional<std::string> problem = audit_problem(t)) throw KineticAuditFailure(*problem);
  }

  void clear() {
    for (Node& node : m_nodes) m_core.cancel(node.event);
    if (m_size > 0) m_core.stats().certificates_live -= m_size - 1;
    m_nodes.clear();
    m_index.reset();
    m_capacity = m_size = 0;
  }

  [[nodiscard]] const KineticSortStats& stats() const { return m_core.stats(); }
  [[nodiscard]] size_t memory_bytes() const {
    size_t bytes = sizeof(*this) + m_nodes.capacity() * sizeof(Node);
    if (m_index) bytes += m_index->memory_bytes();
    return bytes;
  }

 private:
  static constexpr uint32_t kNone = ~0u;
  static constexpr uint32_t kIndexThreshold = 64;  // leaves scanned below, hashed above
  struct Node {
    uint32_t winner = kNone;  ///< front-most id of the subtree (the id itself at a leaf)
    EventHandle event = kNoEvent;  ///< certificate "winner before the other child's winner"
  };

  uint32_t find_leaf(uint32_t id) const {
    if (m_index) {
      const uint32_t leaf = m_index->find(id);
      KINRAY_CHECK_MSG(leaf != detail::IdIndex::kMissing, "id not in the kinetic tournament");
      return leaf;
    }
    for (uint32_t i = 0; i < m_size; ++i)
      if (m_nodes[m_capacity + i].winner == id) return m_capacity + i;
    KINRAY_CHECK_MSG(false, "id not in the kinetic tournament");
    return 0;
  }
  void set_leaf(uint32_t leaf, uint32_t id) {
    m_nodes[leaf].winner = id;
    if (m_index) m_index->set(id, leaf);
  }
  void update_path(uint32_t leaf, double now) {
    for (uint32_t k = leaf / 2; k >= 1; k /= 2) recompute(k, now);
  }

  /// Replays the match at internal node k; returns whether its winner changed.
  bool recompute(uint32_t k, double now) {
    Node& node = m_nodes[k];
    const uint32_t l = m_nodes[2 * k].winner, r = m_nodes[2 * k + 1].winner;
    const uint32_t old = node.winner;
    if (l == kNone || r == kNone) {
      node.winner = l == kNone ? r : l;
      m_core.cancel(node.event);
    } else {
      OrderCertificate c = m_core.certificate(l, r, now);
      if (detail::order_sign(c, now, l, r) > 0) {
        node.winner = l;
        m_core.schedule(node.event, c, l, r, now, m_size, k);
      } else {
        node.winner = r;
        c.negate();
        m_core.schedule(node.event, c, r, l, now, m_size, k);
      }
    }
    return node.winner != old;
  }

  std::vector<uint32_t> leaf_ids() const {
    std::vector<uint32_t> ids;
    ids.reserve(m_size);
    for (uint32_t i = 0; i < m_size; ++i) ids.push_back(m_nodes[m_capacity + i].winner);
    return ids;
  }
  void rebuild(uint32_t capacity, const std::vector<uint32_t>& ids, double now) {
    KINRAY_CHECK(ids.size() <= capacity);
    for (Node& node : m_nodes) m_core.cancel(node.event);
    m_capacity = capacity;
    m_nodes.assign(2 * size_t{capacity}, Node{});
    m_nodes.shrink_to_fit();
    if (capacity > kIndexThreshold) {
      if (!m_index) m_index = std::make_unique<detail::IdIndex>();
      m_index->clear();
    } else {
      m_index.reset();
    }
    m_size = static_cast<uint32_t>(ids.size());
    for (uint32_t i = 0; i < m_size; ++i) set_leaf(capacity + i, ids[i]);
    for (uint32_t k = capacity - 1; k >= 1; --k) recompute(k, now);
  }

  detail::SortCore<Keys> m_core;
  std::vector<Node> m_nodes;  ///< 1-based heap layout, leaves at [m_capacity, 2 m_capacity)
  std::unique_ptr<detail::IdIndex> m_index;  ///< id -> leaf, large only
  uint32_t m_capacity = 0, m_size = 0;
};

}  // namespace kinray
