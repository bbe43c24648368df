#pragma once
// Kinetic heap: a binary heap whose parent-child pairs are the certificates; a failure swaps the
// pair and touches at most five certificates (Basch, Guibas & Hershberger 1997; da Fonseca,
// de Figueiredo & Carvalho, kinetic heap analysis).

#include <algorithm>
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
class KineticHeap {
 public:
  using keys_type = Keys;

  KineticHeap(const Keys& keys, EventQueue& queue, uint32_t owner,
              const KineticSortConfig& config = {})
      : m_core(keys, queue, owner, config) {}
  KineticHeap(KineticHeap&&) noexcept = default;
  KineticHeap& operator=(KineticHeap&&) noexcept = default;
  KineticHeap(const KineticHeap&) = delete;
  KineticHeap& operator=(const KineticHeap&) = delete;

  void insert(uint32_t id, double now) {
    KINRAY_DCHECK(!contains(id));
    m_nodes.push_back(Node{id, kNoEvent});
    if (m_nodes.size() == kIndexThreshold + 1) build_index();
    if (m_index) m_index->set(id, static_cast<uint32_t>(m_nodes.size() - 1));
    if (m_nodes.size() > 1) ++m_core.stats().certificates_live;
    Touched touched;
    sift_up(static_cast<uint32_t>(m_nodes.size() - 1), now, touched);
    reschedule(touched, now);
    if (m_core.audit_on()) audit(now);
  }

  /// Inserts many objects at once: bottom-up heap construction (Floyd), O(n) comparisons, then
  /// every parent-child certificate.
  void insert_all(std::span<const uint32_t> ids, double now) {
    for (Node& node : m_nodes) m_core.cancel(node.event);
    if (!m_nodes.empty()) m_core.stats().certificates_live -= m_nodes.size() - 1;
    for (uint32_t id : ids) m_nodes.push_back(Node{id, kNoEvent});
    if (m_nodes.size() > kIndexThreshold)
      build_index();
    else
      m_index.reset();
    Touched ignored;
    for (auto i = static_cast<uint32_t>(m_nodes.size() / 2); i-- > 0;) {
      ignored.clear();
      sift_down(i, now, ignored);
    }
    if (!m_nodes.empty()) m_core.stats().certificates_live += m_nodes.size() - 1;
    for (uint32_t i = 1; i < m_nodes.size(); ++i) schedule_edge(i, now);
    if (m_core.audit_on()) audit(now);
  }

  void erase(uint32_t id, double now) {
    const uint32_t j = find(id);
    const auto last = static_cast<uint32_t>(m_nodes.size() - 1);
    m_core.cancel(m_nodes[last].event);
    if (m_index) m_index->erase(id);
    Touched touched;
    if (j != last) {
      set_id(j, m_nodes[last].id);
      m_nodes.pop_back();
      touched.push_back(j);
      if (j > 0 && m_core.before(m_nodes[j].id, m_nodes[parent(j)].id, now))
        sift_up(j, now, touched);
      else
        sift_down(j, now, touched);
    } else {
      m_nodes.pop_back();
    }
    if (!m_nodes.empty()) --m_core.stats().certificates_live;
    if (m_nodes.size() == kIndexThreshold) m_index.reset();
    reschedule(touched, now);
    if (m_core.audit_on()) audit(now);
  }

  /// The motion of id changed from now on: recompute the certificates of its node (with its
  /// parent and its children); broken ones get events at now.
  void replace_motion(uint32_t id, double now) {
    Touched touched;
    touched.push_back(find(id));
    reschedule(touched, now);
    if (m_core.audit_on()) audit(now);
  }

  /// The motions of the members for which moved(id) holds changed from now on: the
  /// certificates of their nodes, each once.
  template <class Moved>
  void replace_motions(Moved&& moved, double now) {
    Touched touched;
    for (uint32_t i = 0; i < m_nodes.size(); ++i)
      if (moved(m_nodes[i].id)) touched.push_back(i);
    reschedule(touched, now);
    if (m_core.audit_on()) audit(now);
  }

  void handle_event(uint64_t payload, double now) {
    const auto i = static_cast<uint32_t>(payload);
    KINRAY_CHECK(i >= 1 && i < m_nodes.size());
    m_nodes[i].event = kNoEvent;  // popped
    m_core.begin_event(now);
    const uint32_t p = parent(i);
    const uint32_t a = m_nodes[p].id, b = m_nodes[i].id;
    OrderCertificate c = m_core.certificate(a, b, now);
    KineticSortStats& st = m_core.stats();
    if (detail::order_sign(c, now, a, b) > 0) {
      ++st.events_renewal;
      m_core.schedule(m_nodes[i].event, c, a, b, now, m_nodes.size(), i);
    } else {
      const uint32_t pa = m_nodes[p].id, ch = m_nodes[i].id;
      set_id(p, ch);
      set_id(i, pa);
      c.negate();
      m_core.schedule(m_nodes[i].event, c, b, a, now, m_nodes.size(), i);
      if (p > 0) schedule_edge(p, now);
      const uint32_t sibling = (i % 2 == 1) ? i + 1 : i - 1;
      if (sibling < m_nodes.size()) schedule_edge(sibling, now);
      for (uint32_t child = 2 * i + 1; child <= 2 * i + 2 && child < m_nodes.size(); ++child)
        schedule_edge(child, now);
      ++(p == 0 ? st.events_external : st.events_internal);
    }
    if (m_core.audit_on()) audit(now);
  }

  [[nodiscard]] std::optional<uint32_t> front() const {
    if (m_nodes.empty()) return std::nullopt;
    return m_nodes.front().id;
  }
  [[nodiscard]] size_t size() const { return m_nodes.size(); }
  [[nodiscard]] bool empty() const { return m_nodes.empty(); }
  [[nodiscard]] bool contains(uint32_t id) const {
    if (m_index) return m_index->contains(id);
    return std::any_of(m_nodes.begin(), m_nodes.end(), [id](const Node& n) { return n.id == id; });
  }
  /// f(id) for every object, in heap order (the front first, the rest not sorted).
  template <class F>
  void for_each(F&& f) const {
    for (const Node& n : m_nodes) f(n.id);
  }

  /// Every parent-child certificate recomputed at t holds just after t or is pending at t.
  /// The first problem found, or nothing; never aborts, so the owner can add where it was found.
  [[nodiscard]] std::optional<std::string> audit_problem(double t) const {
    if (!m_nodes.empty() && m_nodes[0].event != kNoEvent)
      return std::string("kinetic heap: the root has an event");
    for (uint32_t i = 1; i < m_nodes.size(); ++i) {
      if (m_nodes[i].event != kNoEvent && m_core.queue().payload(m_nodes[i].event) != i)
        return "kinetic heap: node " + std::to_string(i) + " has an event of another node";
      if (auto problem = m_core.pair_problem(m_nodes[parent(i)].id, m_nodes[i].id, m_nodes[i].event, t))
        return problem;
    }
    return std::nullopt;
  }
  /// Throws KineticAuditFailure with audit_problem(t), if any.
  void audit(double t) const {
    if (std::optional<std::string> problem = audit_problem(t)) throw KineticAuditFailure(*problem);
  }

  void clear() {
    for (Node& node : m_nodes) m_core.cancel(node.event);
    if (!m_nodes.empty()) m_core.stats().certificates_live -= m_nodes.size() - 1;
    m_nodes.clear();
    m_index.reset();
  }

  [[nodiscard]] const KineticSortStats& stats() const { return m_core.stats(); }
  [[nodiscard]] size_t memory_bytes() const {
    size_t bytes = sizeof(*this) + m_nodes.capacity() * sizeof(Node);
    if (m_index) bytes += m_index->memory_bytes();
    return bytes;
  }

 private:
  static constexpr size_t kIndexThreshold = 64;  // ids scanned below, hashed above
  struct Node {
    uint32_t id;
    EventHandle event;  ///< certificate "parent before this", kNoEvent at the root
  };
  // Nodes whose id changed; their own and their children's certificates are recomputed.
  using Touched = std::vector<uint32_t>;

  static uint32_t parent(uint32_t i) { return (i - 1) / 2; }

  uint32_t find(uint32_t id) const {
    if (m_index) {
      const uint32_t pos = m_index->find(id);
      KINRAY_CHECK_MSG(pos != detail::IdIndex::kMissing, "id not in the kinetic heap");
      return pos;
    }
    for (uint32_t i = 0; i < m_nodes.size(); ++i)
      if (m_nodes[i].id == id) return i;
    KINRAY_CHECK_MSG(false, "id not in the kinetic heap");
    return 0;
  }
  void set_id(uint32_t i, uint32_t id) {
    m_nodes[i].id = id;
    if (m_index) m_index->set(id, i);
  }
  void build_index() {
    m_index = std::make_unique<detail::IdIndex>();
    for (uint32_t i = 0; i < m_nodes.size(); ++i) m_index->set(m_nodes[i].id, i);
  }

  void sift_up(uint32_t i, double now, Touched& touched) {
    touched.push_back(i);
    while (i > 0 && m_core.before(m_nodes[i].id, m_nodes[parent(i)].id, now)) {
      const uint32_t p = parent(i);
      const uint32_t x = m_nodes[i].id, y = m_nodes[p].id;
      set_id(i, y);
      set_id(p, x);
      touched.push_back(p);
      i = p;
    }
  }
  void sift_down(uint32_t i, double now, Touched& touched) {
    touched.push_back(i);
    const auto n = static_cast<uint32_t>(m_nodes.size());
    for (;;) {
      uint32_t best = i;
      const uint32_t l = 2 * i + 1, r = 2 * i + 2;
      if (l < n && m_core.before(m_nodes[l].id, m_nodes[best].id, now)) best = l;
      if (r < n && m_core.before(m_nodes[r].id, m_nodes[best].id, now)) best = r;
      if (best == i) return;
      const uint32_t x = m_nodes[i].id, y = m_nodes[best].id;
      set_id(i, y);
      set_id(best, x);
      touched.push_back(best);
      i = best;
    }
  }
  void schedule_edge(uint32_t i, double now) {
    const uint32_t a = m_nodes[parent(i)].id, b = m_nodes[i].id;
    m_core.schedule(m_nodes[i].event, m_core.certificate(a, b, now), a, b, now, m_nodes.size(),
                    i);
  }
  void reschedule(Touched& touched, double now) {
    Touched edges;
    const auto n = static_cast<uint32_t>(m_nodes.size());
    for (uint32_t i : touched) {
      if (i >= n) continue;
      if (i > 0) edges.push_back(i);
      for (uint32_t child = 2 * i + 1; child <= 2 * i + 2 && child < n; ++child)
        edges.push_back(child);
    }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (uint32_t i : edges) schedule_edge(i, now);
  }

  detail::SortCore<Keys> m_core;
  std::vector<Node> m_nodes;  ///< implicit binary heap, root at 0
  std::unique_ptr<detail::IdIndex> m_index;  ///< id -> node, large only
};

}  // namespace kinray
