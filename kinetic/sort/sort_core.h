#pragma once
// What the kinetic sorted list, tournament and heap share in their implementation
// (detail::SortCore): the keys, the event queue, the statistics and the same-instant guard, the
// scheduling of certificates and their audit.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "kinetic/core/audit_failure.h"
#include "kinetic/core/certificate_schedule.h"
#include "kinetic/core/event_queue.h"
#include "kinetic/core/exact_certificate.h"
#include "kinetic/core/polynomial.h"
#include "kinetic/core/root_finding.h"
#include "kinetic/sort/sort_config.h"
#include "kinetic/sort/sort_keys.h"
#include "kinetic/sort/sort_stats.h"
#include "util/check.h"

namespace kinray {
namespace detail {

/// Absolute key values audit tolerance: a before b requires value(a) <= value(b) + tol.
[[nodiscard]] double value_tolerance(double va, double vb);

inline uint64_t pair_code(uint32_t a, uint32_t b) { return (uint64_t{a} << 32) | b; }

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
}  // namespace kinray
