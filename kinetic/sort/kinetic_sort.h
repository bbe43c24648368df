#pragma once
// Kinetic sorting: the shared concept, configuration and statistics of the kinetic sorted list,
// tournament and heap, plus simple key models (LinearMotionKeys, PolynomialKeys).
//
// Conventions shared by the three structures (see docs/kinetic_core.md, "Kinetic core"):
// - "a before b" holds while the certificate polynomial is > 0; at an instant where it is 0 the
//   sign just after (sign_after) decides; if it is the zero polynomial (identical motions) the
//   smaller id comes first. Exact ties are thus broken by id, deterministically.
// - Events are pushed with EventKey{time, config.event_kind, owner, (left id << 32) | right id}
//   and a payload private to the structure. Whoever pops the queue calls handle_event(payload,
//   now) AFTER popping (the Simulator does so).
// - Keys contract: while neither motion changes, order_certificate(a, b, t) returns the same
//   origin at every t (e.g. the start of the current motion segments, not t itself), and
//   order_certificate(b, a, t).f is exactly -order_certificate(a, b, t).f (e.g. computed as
//   key_b - key_a coefficient-wise). Then an event is never re-fired at the instant it was
//   processed. Keys that re-centre at t still work but may cost extra events at near-ties.

#include <algorithm>
#include <bit>
#include <cmath>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kinetic/core/audit_failure.h"
#include "kinetic/core/certificate_schedule.h"
#include "kinetic/core/counters.h"
#include "kinetic/core/event_queue.h"
#include "kinetic/core/exact_certificate.h"
#include "kinetic/core/polynomial.h"
#include "kinetic/core/quality_measures.h"
#include "kinetic/core/root_finding.h"
#include "util/check.h"

namespace kinray {

template <class K>
concept KineticKeys = requires(const K& k, uint32_t a, uint32_t b, double t) {
  { k.order_certificate(a, b, t) } -> std::same_as<OrderCertificate>;  // t = now; valid from now on
  { k.value(a, t) } -> std::convertible_to<double>;  // the key at time t, for audit / brute force
};

/// Keys may also hand on a proof of order (OrderCertificate::separator): when `to` replaces
/// `from` in a sort (a pixel's triangle handing over to its neighbour across an edge) and the
/// certificate of `kept` and `from` carried a separator, order_certificate_beside(kept, from, to,
/// now, separator, side) returns the certificate of (kept, to) if `to` provably stays on `side` of
/// the separator (+1: after it, so kept before to; -1: before it) through the window of (kept,
/// from)'s certificate, which must be (kept, to)'s too; std::nullopt when it cannot tell, and the
/// sort computes order_certificate(kept, to, now). `kept`'s side was proved with the separator for
/// that whole window, so its motion is not looked at.
template <class K>
concept SeparatorKeys = KineticKeys<K> &&
    requires(const K& k, uint32_t a, double t, float separator, int side) {
  {
    k.order_certificate_beside(a, a, a, t, separator, side)
    } -> std::same_as<std::optional<OrderCertificate>>;
};

/// Keys may also say that two keys are equal at t although their values, evaluated in double,
/// differ beyond the audit's tolerance (`bool tied(a, b, t) const`): the audit then accepts
/// either order of that pair at t.
template <class K>
[[nodiscard]] bool keys_tied(const K& keys, uint32_t a, uint32_t b, double t) {
  if constexpr (requires { keys.tied(a, b, t); })
    return keys.tied(a, b, t);
  else
    return false;
}

struct KineticSortStats;

struct KineticSortConfig {
  uint32_t event_kind = 0;  ///< EventKey.kind of every event of the structure
  bool audit = false;       ///< audit(now) after every handled event and every update
  /// When non-null the structure adds its counters here instead of keeping its own (many small
  /// instances, one total); stats() then returns this object.
  KineticSortStats* shared_stats = nullptr;
  /// A certificate that holds to the end of its motions' segment gets a renewal event there.
  /// An owner that recomputes every certificate of a switched motion at that instant, before any
  /// event of the structure at the same time, sets this false: the renewal would never be popped,
  /// only pushed, moved and cancelled.
  bool renew_at_segment_end = true;
};

// X(member, "stats key") of KineticSortStats.
#define KINRAY_SORT_COUNTERS(X)                                                              \
  X(events_internal, "events_internal") /* failures that did not change the front */        \
  X(events_external, "events_external") /* failures that changed the front */              \
  X(events_renewal, "events_renewal")   /* at a certificate's end, or spurious: no change */ \
  X(certificates_live, "certificates_live")       /* held now (a gauge) */                  \
  X(certificates_created, "certificates_created") /* computed and (re)scheduled */          \
  X(work, "work")             /* certificate computations, comparisons included */          \
  X(degenerate, "degenerate") /* near-ties resolved by the same-instant guard */             \
  X(exact_deferred, "exact_deferred") /* exact failure searches put off to a recheck */

/// Counters of one structure (or of many, when shared).
struct KineticSortStats {
  KINRAY_COUNTERS(KineticSortStats, KINRAY_SORT_COUNTERS)
  [[nodiscard]] uint64_t events() const { return events_internal + events_external; }
};

/// What the quality measures of a sort over `objects` keys are computed from. The sorts keep
/// no maximum of their live certificates: compactness is the count held now.
[[nodiscard]] QualityCounts quality_counts(const KineticSortStats& stats, size_t objects);

/// The common interface of KineticSortedList, KineticTournament and KineticHeap.
template <class S>
concept KineticSort =
    requires(S& s, const S& cs, uint32_t id, double t, uint64_t payload) {
      typename S::keys_type;
      requires KineticKeys<typename S::keys_type>;
      requires std::constructible_from<S, const typename S::keys_type&, EventQueue&, uint32_t,
                                       const KineticSortConfig&>;
      s.insert(id, t);
      s.erase(id, t);
      s.replace_motion(id, t);
      s.handle_event(payload, t);
      { cs.front() } -> std::same_as<std::optional<uint32_t>>;
      { cs.size() } -> std::convertible_to<size_t>;
      { cs.contains(id) } -> std::same_as<bool>;
      cs.audit(t);
      { cs.audit_problem(t) } -> std::same_as<std::optional<std::string>>;
      { cs.stats() } -> std::same_as<const KineticSortStats&>;
    };

namespace detail {

/// Absolute key values audit tolerance: a before b requires value(a) <= value(b) + tol.
[[nodiscard]] double value_tolerance(double va, double vb);

inline uint64_t pair_code(uint32_t a, uint32_t b) { return (uint64_t{a} << 32) | b; }

/// id -> position for the larger instances of the tournament and heap: open addressing with
/// linear probing (load <= 1/2), backward-shift deletion; one flat array, no nodes. The id ~0u is
/// reserved.
class IdIndex {
 public:
  static constexpr uint32_t kMissing = ~0u;

  [[nodiscard]] uint32_t find(uint32_t id) const {
    if (m_table.empty()) return kMissing;
    for (size_t i = home(id);; i = (i + 1) & mask()) {
      if (m_table[i].id == id) return m_table[i].pos;
      if (m_table[i].id == kEmpty) return kMissing;
    }
  }
  [[nodiscard]] bool contains(uint32_t id) const { return find(id) != kMissing; }
  void set(uint32_t id, uint32_t pos) {
    KINRAY_DCHECK(id != kEmpty);
    if (2 * (m_size + 1) > m_table.size()) rehash(m_table.empty() ? 16 : 2 * m_table.size());
    size_t i = home(id);
    while (m_table[i].id != kEmpty && m_table[i].id != id) i = (i + 1) & mask();
    if (m_table[i].id == kEmpty) ++m_size;
    m_table[i] = {id, pos};
  }
  void erase(uint32_t id) {
    if (m_table.empty()) return;
    size_t i = home(id);
    while (m_table[i].id != id) {
      if (m_table[i].id == kEmpty) return;
      i = (i + 1) & mask();
    }
    // Backward shift: move later entries of the probe run into the hole when allowed.
    for (size_t j = (i + 1) & mask(); m_table[j].id != kEmpty; j = (j + 1) & mask()) {
      const size_t k = home(m_table[j].id);
      const bool movable = i <= j ? (k <= i || k > j) : (k <= i && k > j);
      if (movable) {
        m_table[i] = m_table[j];
        i = j;
      }
    }
    m_table[i].id = kEmpty;
    --m_size;
  }
  void clear() {
    m_table.clear();
    m_size = 0;
  }
  [[nodiscard]] size_t size() const { return m_size; }
  [[nodiscard]] size_t memory_bytes() const { return m_table.capacity() * sizeof(Entry); }

 private:
  static constexpr uint32_t kEmpty = ~0u;
  struct Entry {
    uint32_t id = kEmpty;
    uint32_t pos = 0;
  };
  size_t mask() const { return m_table.size() - 1; }
  size_t home(uint32_t id) const {
    return static_cast<size_t>((uint64_t{id} * 0x9E3779B97F4A7C15ull) >> m_shift);
  }
  void rehash(size_t capacity) {
    std::vector<Entry> old = std::move(m_table);
    m_table.assign(capacity, Entry{});
    m_shift = 64 - std::countr_zero(capacity);
    m_size = 0;
    for (const Entry& e : old)
      if (e.id != kEmpty) set(e.id, e.pos);
  }
  std::vector<Entry> m_table;
  size_t m_size = 0;
  int m_shift = 64;
};

/// What every kinetic sort instance holds besides its own topology: the keys, the queue, the
/// event identity, the statistics (own or shared), and the same-instant guard.
template <class Keys>
class SortCore {
 public:
  SortCore(const Keys& keys, EventQueue& queue, uint32_t owner, const KineticSortConfig& config)
      : m_keys(&keys),
        m_queue(&queue),
        m_owner(owner),
        m_kind(config.event_kind),
        m_audit(config.audit),
        m_renew(config.renew_at_segment_end) {
    if (config.shared_stats) {
      m_stats = config.shared_stats;
    } else {
      m_own = std::make_unique<KineticSortStats>();
      m_stats = m_own.get();
    }
  }
  const Keys& keys() const { return *m_keys; }
  EventQueue& queue() const { return *m_queue; }
  KineticSortStats& stats() const { return *m_stats; }
  bool audit_on() const { return m_audit; }

  /// Certificate of (a, b) at now, counted as work.
  OrderCertificate certificate(uint32_t a, uint32_t b, double now) const {
    ++m_stats->work;
    return m_keys->order_certificate(a, b, now);
  }
  /// The certificate of (kept, to) where `to` replaces `from`, whose certificate with `kept`
  /// carried `separator` and put `to`'s side at `side`: from the separator when the keys can
  /// (SeparatorKeys), else computed. Counted as work either way.
  OrderCertificate certificate_replacing(uint32_t kept, uint32_t from, uint32_t to, float separator,
                                         int side, double now) const {
    if constexpr (SeparatorKeys<Keys>) {
      if (!std::isnan(separator))
        if (std::optional<OrderCertificate> c =
                m_keys->order_certificate_beside(kept, from, to, now, separator, side)) {
          ++m_stats->work;
          return *std::move(c);
        }
    }
    return certificate(kept, to, now);
  }
  /// "a before b" just after now (the id rule for identical motions).
  bool before(uint32_t a, uint32_t b, double now) const {
    return order_sign(certificate(a, b, now), now, a, b) > 0;
  }

  /// Called at the start of handle_event: counts events at the same instant.
  void begin_event(double now) {
    if (now != m_instant_time) {
      m_instant_time = now;
      m_instant_events = 0;
    }
    ++m_instant_events;
  }

  /// (Re)schedules the event of certificate c of (a, b) whose handle is `handle`, or cancels it.
  void schedule(EventHandle& handle, const OrderCertificate& c, uint32_t a, uint32_t b,
                double now, size_t n, uint64_t payload) {
    Schedule s = schedule_certificate(c, now, a, b, /*defer_exact=*/true);
    if (s.recheck) ++m_stats->exact_deferred;
    if (!m_renew && !s.failure && !s.recheck && !s.degenerate)
      s.time = std::numeric_limits<double>::infinity();  // the owner renews it (the config)
    if (s.failure && s.time == now && now == m_instant_time && m_instant_events > budget(n)) {
      s = schedule_degenerate(c, now, a, b);
      ++m_stats->degenerate;
      m_tolerate_until = std::max(m_tolerate_until, s.broken_until);
    }
    ++m_stats->certificates_created;
    m_queue->schedule(handle, EventKey{s.time, m_kind, m_owner, pair_code(a, b)}, payload);
  }
  void cancel(EventHandle& handle) { m_queue->cancel(handle); }

  /// Audit of one certificate of (a, b) whose event is `handle`, at time t: the problem, naming
  /// the pair, the key values and the certificate, or nothing if it holds. Never aborts or throws,
  /// so the owner can add where it was found.
  [[nodiscard]] std::optional<std::string> pair_problem(uint32_t a, uint32_t b, EventHandle handle,
                                                        double t) const {
    const OrderCertificate c = m_keys->order_certificate(a, b, t);
    const bool pending = handle != kNoEvent;
    const double at = pending ? m_queue->key(handle).time : std::numeric_limits<double>::infinity();
    const char* problem = nullptr;
    Schedule s;
    if (pending && m_queue->key(handle).a != m_owner) {
      problem = "event of another owner";
    } else if (at < t) {
      problem = "audit after a pending event time: events not processed";
    } else if (order_sign(c, t, a, b) < 0) {
      if (!(at <= t || t <= m_tolerate_until)) problem = "certificate broken, no pending event";
    } else if (at > t && t > m_tolerate_until) {
      // Holds and nothing pending now: values in order, failure not scheduled too late. A key
      // with no value at t (a triangle collapsed into the eye: its depth is 0/0 there) is ordered
      // by the certificate's sign just after t alone, checked above.
      const double va = m_keys->value(a, t), vb = m_keys->value(b, t);
      s = schedule_certificate(c, t, a, b);
      if (!std::isnan(va) && !std::isnan(vb) && !(va <= vb + value_tolerance(va, vb)) &&
          !keys_tied(*m_keys, a, b, t))
        problem = "key values out of order";
      else if (s.failure && !(at <= s.time + 1e-7 * (1 + std::abs(s.time))))
        problem = "certificate failure scheduled too late";
    }
    if (problem == nullptr) return std::nullopt;
    char text[512];
    int n = std::snprintf(text, sizeof text,
                          "kinetic sort audit (owner %u) at t = %.17g: pair (%u, %u): %s; key "
                          "values %.17g, %.17g; scheduled %.17g, recomputed %.17g, origin %.17g, "
                          "end %.17g, f degree %d:",
                          m_owner, t, a, b, problem, m_keys->value(a, t), m_keys->value(b, t), at,
                          s.time, c.origin, c.end, c.f.degree);
    std::string message(text, size_t(std::clamp(n, 0, int(sizeof text) - 1)));
    for (int k = 0; k <= c.f.degree; ++k) {
      n = std::snprintf(text, sizeof text, " %.17g", c.f.c[size_t(k)]);
      message.append(text, size_t(std::clamp(n, 0, int(sizeof text) - 1)));
    }
    if (c.exact) message += " (decided exactly)";
    return message;
  }

 private:
  static uint64_t budget(size_t n) {
    return 64 + 4 * uint64_t{n} * std::min<uint64_t>(n, 64);
  }
  const Keys* m_keys;
  EventQueue* m_queue;
  KineticSortStats* m_stats = nullptr;
  std::unique_ptr<KineticSortStats> m_own;
  uint32_t m_owner;
  uint32_t m_kind;
  bool m_audit;
  bool m_renew;  ///< KineticSortConfig::renew_at_segment_end
  uint32_t m_instant_events = 0;
  double m_instant_time = -std::numeric_limits<double>::infinity();
  double m_tolerate_until = -std::numeric_limits<double>::infinity();
};

}  // namespace detail

/// Keys moving linearly: key_i(t) = x_i + v_i t (absolute time, certificate origin 0).
/// Motion can be replaced (set_velocity / set_motion) keeping the same origin convention.
class LinearMotionKeys {
 public:
  uint32_t add(double x0, double v) {
    m_lines.push_back({x0, v});
    return static_cast<uint32_t>(m_lines.size() - 1);
  }
  /// From now on key(t) = x0 + v t (x0 is the value at time 0 of the new line); then call
  /// replace_motion(id, now) on the structures holding id.
  void set_motion(uint32_t id, double x0, double v) { m_lines[id] = {x0, v}; }
  [[nodiscard]] size_t size() const { return m_lines.size(); }
  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double /*t*/) const {
    const Line& la = m_lines[a];
    const Line& lb = m_lines[b];
    OrderCertificate c;
    c.f.c[0] = lb.x0 - la.x0;
    c.f.c[1] = lb.v - la.v;
    c.f.degree = 1;
    return c;
  }
  [[nodiscard]] double value(uint32_t a, double t) const {
    return m_lines[a].x0 + m_lines[a].v * t;
  }

 private:
  struct Line {
    double x0, v;  // interleaved: one cache line access per object
  };
  std::vector<Line> m_lines;
};

/// Keys that are piecewise polynomials of time: object id follows segment k from its start on,
/// key(t) = p_k(t - start_k). Certificates use the origin max(start_a, start_b) and end at the
/// next segment start of either object (so a structure renews them there by itself).
class PolynomialKeys {
 public:
  uint32_t add(const Polynomial& p, double start = 0);
  /// A new object with exactly the motion (all segments) of `other`: equal keys.
  uint32_t add_copy(uint32_t other);
  /// From `start` on, key(t) = p(t - start); later segments are dropped. Then call
  /// replace_motion(id, now) on the structures holding id.
  void set_motion(uint32_t id, const Polynomial& p, double start);
  /// Append a segment beginning at start (> the last start). Certificates computed before do not
  /// know their new end: call replace_motion(id, now) on the structures holding id.
  void append_motion(uint32_t id, const Polynomial& p, double start);
  [[nodiscard]] size_t size() const { return m_objects.size(); }
  [[nodiscard]] OrderCertificate order_certificate(uint32_t a, uint32_t b, double t) const;
  [[nodiscard]] double value(uint32_t a, double t) const;

 private:
  struct Segment {
    double start = 0;
    Polynomial p;
  };
  struct Active {
    const Segment* seg;
    double next_start;
  };
  [[nodiscard]] Active active(uint32_t id, double t) const;
  std::vector<std::vector<Segment>> m_objects;
};

static_assert(KineticKeys<LinearMotionKeys>);
static_assert(KineticKeys<PolynomialKeys>);

}  // namespace kinray
