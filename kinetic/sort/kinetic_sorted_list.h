#pragma once
// Kinetic sorted list: one certificate per adjacent pair; a swap reschedules at most three
// (Basch, Guibas & Hershberger 1997, kinetic sorting).

#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "kinetic/sort/kinetic_sort.h"
#include "kinetic/sort/sort_core.h"
#include "util/small_vector.h"

namespace kinray {

template <KineticKeys Keys>
class KineticSortedList {
 public:
  using keys_type = Keys;

  KineticSortedList(const Keys& keys, EventQueue& queue, uint32_t owner,
                    const KineticSortConfig& config = {})
      : m_core(keys, queue, owner, config) {}
  KineticSortedList(KineticSortedList&&) noexcept = default;
  KineticSortedList& operator=(KineticSortedList&&) noexcept = default;
  KineticSortedList(const KineticSortedList&) = delete;
  KineticSortedList& operator=(const KineticSortedList&) = delete;

  /// O(log n) certificate comparisons to find the place, O(n) to shift the entries after it. The
  /// search's last comparison on each side is with the new neighbours, so their certificates are
  /// scheduled as the search computed them: (front, id) as is, (id, back) negated (exactly -f,
  /// the keys contract), none computed twice.
  void insert(uint32_t id, double now) {
    KINRAY_DCHECK(!contains(id));
    const size_t n = m_entries.size();
    if (n == 0) {  // no neighbour, no certificate: most inserts of a grid's pixels
      m_entries.push_back(Entry{id, kNoEvent});
      if (m_core.audit_on()) audit(now);
      return;
    }
    OrderCertificate with_front, with_back;  // of (entry lo - 1, id) and (entry lo, id)
    size_t lo = 0, hi = n;
    while (lo < hi) {
      const size_t mid = (lo + hi) / 2;
      const uint32_t other = m_entries[mid].id;
      OrderCertificate c = m_core.certificate(other, id, now);
      if (detail::order_sign(c, now, other, id) > 0) {
        lo = mid + 1;
        with_front = std::move(c);
      } else {
        hi = mid;
        with_back = std::move(c);
      }
    }
    m_entries.insert(m_entries.begin() + static_cast<std::ptrdiff_t>(lo), Entry{id, kNoEvent});
    renumber(lo + 1);
    if (n > 0) ++m_core.stats().certificates_live;
    if (lo > 0) schedule(lo - 1, with_front, now);
    if (lo < n) {
      with_back.negate();
      schedule(lo, with_back, now);
    }
    if (m_core.audit_on()) audit(now);
  }

  /// Inserts many objects at once: sorted by key value at now (ties by id), then every adjacent
  /// certificate is computed; any pair the certificates order differently (a near-tie) gets an
  /// event at now. O(n log n) value reads and O(n) certificates.
  void insert_all(std::span<const uint32_t> ids, double now) {
    for (Entry& e : m_entries) m_core.cancel(e.event);
    if (!m_entries.empty()) m_core.stats().certificates_live -= m_entries.size() - 1;
    std::vector<std::pair<double, uint32_t>> order;
    order.reserve(m_entries.size() + ids.size());
    for (const Entry& e : m_entries) order.push_back({m_core.keys().value(e.id, now), e.id});
    for (uint32_t id : ids) order.push_back({m_core.keys().value(id, now), id});
    std::sort(order.begin(), order.end());
    m_entries.clear();
    m_entries.reserve(order.size());
    for (const auto& [value, id] : order) m_entries.push_back(Entry{id, kNoEvent});
    if (!m_entries.empty()) m_core.stats().certificates_live += m_entries.size() - 1;
    for (size_t i = 0; i + 1 < m_entries.size(); ++i) schedule(i, now);
    if (m_core.audit_on()) audit(now);
  }

  void erase(uint32_t id, double now) {
    const size_t p = position(id);
    const size_t n = m_entries.size();
    m_core.cancel(m_entries[p].event);
    m_entries.erase(m_entries.begin() + static_cast<std::ptrdiff_t>(p));
    renumber(p);
    if (n > 1) --m_core.stats().certificates_live;
    if (p > 0) {
      if (p < n - 1)
        schedule(p - 1, now);
      else
        m_core.cancel(m_entries[p - 1].event);
    }
    if (m_core.audit_on()) audit(now);
  }

  /// The only object becomes `id` (no pair, so no certificate changes): one erase and one
  /// insert, as a pixel's sole triangle hands over to its neighbour across the edge.
  void rename_sole(uint32_t id) {
    KINRAY_CHECK(m_entries.size() == 1);
    m_entries[0].id = id;
  }

  /// Of two objects, `from` leaves and `to` enters at now: what erase(from) then insert(to) do,
  /// the one certificate insert computes (of the other object and `to`), and the pair's event
  /// moved to its time rather than cancelled and pushed again.
  void replace_in_pair(uint32_t from, uint32_t to, double now) {
    KINRAY_CHECK(m_entries.size() == 2);
    const size_t p = m_entries[0].id == from ? 0 : 1;
    KINRAY_CHECK_MSG(m_entries[p].id == from, "id not in the kinetic sorted list");
    const uint32_t other = m_entries[1 - p].id;
    // The pair's certificate put `from` after its separator when `from` was second.
    OrderCertificate c =
        m_core.certificate_replacing(other, from, to, m_entries[0].separator, p == 1 ? 1 : -1, now);
    if (detail::order_sign(c, now, other, to) > 0) {
      m_entries[0].id = other;
      m_entries[1].id = to;
    } else {
      m_entries[0].id = to;
      m_entries[1].id = other;
      c.negate();
    }
    schedule(0, c, now);
    if (m_core.audit_on()) audit(now);
  }

  /// `from` leaves and `to` takes its place at now, where `to` is at `from`'s key (a pixel's
  /// triangle handing over to its neighbour across the edge the ray crosses: both planes hold
  /// the edge's point on the ray). When the certificates of `to` with `from`'s two neighbours
  /// keep them on their sides, those two are scheduled (the ones erase then insert would leave:
  /// insert's last comparison on each side is with the new neighbours) and the erase's
  /// certificate between the two neighbours, and insert's comparisons beyond them, are spared;
  /// true. Otherwise nothing changes and false: the caller erases and inserts.
  bool replace_in_place(uint32_t from, uint32_t to, double now) {
    const size_t p = position(from);
    const size_t n = m_entries.size();
    OrderCertificate with_front, with_back;
    // `from` is after the separator of its pair with the front, before that with the back.
    if (p > 0) {
      const uint32_t front = m_entries[p - 1].id;
      with_front =
          m_core.certificate_replacing(front, from, to, m_entries[p - 1].separator, 1, now);
      if (detail::order_sign(with_front, now, front, to) <= 0) return false;
    }
    if (p + 1 < n) {
      const uint32_t back = m_entries[p + 1].id;
      with_back = m_core.certificate_replacing(back, from, to, m_entries[p].separator, -1, now);
      if (detail::order_sign(with_back, now, back, to) > 0) return false;
    }
    m_entries[p].id = to;
    if (p > 0) schedule(p - 1, with_front, now);
    if (p + 1 < n) {
      with_back.negate();
      schedule(p, with_back, now);
    }
    if (m_core.audit_on()) audit(now);
    return true;
  }

  /// The motion of id changed from now on: recompute its (at most two) certificates. Pairs that
  /// are out of order now get events at now, processed next by the queue's owner.
  void replace_motion(uint32_t id, double now) {
    const size_t p = position(id);
    if (p > 0) schedule(p - 1, now);
    if (p + 1 < m_entries.size()) schedule(p, now);
    if (m_core.audit_on()) audit(now);
  }

  /// The motions of the members for which moved(id) holds changed from now on (a flightplan
  /// update of their meshes): every certificate with a moved member is recomputed, once, where
  /// replace_motion on each would compute a pair of two moved members twice.
  template <class Moved>
  void replace_motions(Moved&& moved, double now) {
    for (size_t i = 0; i + 1 < m_entries.size(); ++i)
      if (moved(m_entries[i].id) || moved(m_entries[i + 1].id)) schedule(i, now);
    if (m_core.audit_on()) audit(now);
  }

  /// The event with this payload was popped from the queue; now = its time.
  void handle_event(uint64_t payload, double now) {
    const auto i = static_cast<size_t>(payload);
    KINRAY_CHECK(i + 1 < m_entries.size());
    m_entries[i].event = kNoEvent;  // popped
    if (i > 0) m_core.queue().prefetch(m_entries[i - 1].event);
    if (i + 2 < m_entries.size()) m_core.queue().prefetch(m_entries[i + 1].event);
    m_core.begin_event(now);
    const uint32_t a = m_entries[i].id, b = m_entries[i + 1].id;
    OrderCertificate c = m_core.certificate(a, b, now);
    KineticSortStats& st = m_core.stats();
    if (detail::order_sign(c, now, a, b) > 0) {
      ++st.events_renewal;
      schedule(i, c, now);
    } else {
      std::swap(m_entries[i].id, m_entries[i + 1].id);
      c.negate();
      schedule(i, c, now);
      if (i > 0) schedule(i - 1, now);
      if (i + 2 < m_entries.size()) schedule(i + 1, now);
      ++(i == 0 ? st.events_external : st.events_internal);
    }
    if (m_core.audit_on()) audit(now);
  }

  [[nodiscard]] std::optional<uint32_t> front() const {
    if (m_entries.empty()) return std::nullopt;
    return m_entries.front().id;
  }
  [[nodiscard]] size_t size() const { return m_entries.size(); }
  [[nodiscard]] bool empty() const { return m_entries.empty(); }
  [[nodiscard]] bool contains(uint32_t id) const {
    return std::any_of(m_entries.begin(), m_entries.end(),
                       [id](const Entry& e) { return e.id == id; });
  }
  /// The i-th object in order.
  [[nodiscard]] uint32_t at(size_t i) const { return m_entries[i].id; }

  /// f(id) for every object, front to back.
  template <class F>
  void for_each_in_order(F&& f) const {
    for (const Entry& e : m_entries) f(e.id);
  }
  /// f(id) for every object (front to back), as the tournament and the heap offer it.
  template <class F>
  void for_each(F&& f) const {
    for_each_in_order(f);
  }

  /// Every adjacent certificate recomputed at t: holds just after t, or its event is pending at t
  /// (simultaneous events); key values in order; no failure scheduled later than recomputed.
  /// The first problem found, or nothing; never aborts, so the owner can add where it was found.
  [[nodiscard]] std::optional<std::string> audit_problem(double t) const {
    for (size_t i = 0; i + 1 < m_entries.size(); ++i)
      if (auto problem = m_core.pair_problem(m_entries[i].id, m_entries[i + 1].id, m_entries[i].event, t))
        return problem;
    for (size_t i = 0; i < m_entries.size(); ++i)
      if (m_entries[i].event != kNoEvent &&
          !(i + 1 < m_entries.size() && m_core.queue().payload(m_entries[i].event) == i))
        return "kinetic sorted list: entry " + std::to_string(i) + " has an event of another certificate";
    if (!(m_core.stats().certificates_live >= (m_entries.empty() ? 0 : m_entries.size() - 1)))
      return std::string("kinetic sorted list: fewer live certificates counted than adjacent pairs");
    return std::nullopt;
  }
  /// Throws KineticAuditFailure with audit_problem(t), if any.
  void audit(double t) const {
    if (std::optional<std::string> problem = audit_problem(t)) throw KineticAuditFailure(*problem);
  }

  /// Removes every event of this structure from the queue and empties it.
  void clear() {
    for (Entry& e : m_entries) m_core.cancel(e.event);
    if (!m_entries.empty()) m_core.stats().certificates_live -= m_entries.size() - 1;
    m_entries.clear();
  }

  [[nodiscard]] const KineticSortStats& stats() const { return m_core.stats(); }
  /// Bytes held by this instance (not counting its events in the shared queue).
  [[nodiscard]] size_t memory_bytes() const {
    return sizeof(*this) + m_entries.heap_bytes();
  }

 private:
  struct Entry {
    uint32_t id;
    EventHandle event;  ///< event of the certificate (this, next), or kNoEvent
    /// That certificate's separator (NaN when none): a replacement of either is compared with it.
    float separator = std::numeric_limits<float>::quiet_NaN();
  };

  size_t position(uint32_t id) const {
    for (size_t p = 0; p < m_entries.size(); ++p)
      if (m_entries[p].id == id) return p;
    KINRAY_CHECK_MSG(false, "id not in the kinetic sorted list");
    return 0;
  }
  void renumber(size_t from) {
    for (size_t j = from; j < m_entries.size(); ++j)
      if (m_entries[j].event != kNoEvent) m_core.queue().set_payload(m_entries[j].event, j);
  }
  void schedule(size_t i, double now) {
    schedule(i, m_core.certificate(m_entries[i].id, m_entries[i + 1].id, now), now);
  }
  /// Schedules c, the certificate of entries i and i + 1, and keeps its separator.
  void schedule(size_t i, const OrderCertificate& c, double now) {
    m_entries[i].separator = c.separator;
    m_core.schedule(m_entries[i].event, c, m_entries[i].id, m_entries[i + 1].id, now,
                    m_entries.size(), i);
  }

  detail::SortCore<Keys> m_core;
  /// Two inline: most pixels of the kinetic grid hold one or two triangles.
  SmallVector<Entry, 2> m_entries;
};

}  // namespace kinray
