#pragma once
// The kinetic simulator: a clock and an event queue (CGAL's kinetic Simulator, reduced).

#include <cstdint>
#include <utility>

#include "kinetic/core/event_queue.h"
#include "util/check.h"

namespace kinray {

class Simulator {
 public:
  explicit Simulator(double start_time = 0) : m_now(start_time) {}

  [[nodiscard]] double now() const { return m_now; }
  /// Sets the clock of a simulator that has not run yet (no event pushed or handled).
  void start_at(double t) {
    KINRAY_CHECK(m_queue.empty() && m_events == 0);
    m_now = t;
  }
  [[nodiscard]] EventQueue& queue() { return m_queue; }
  [[nodiscard]] const EventQueue& queue() const { return m_queue; }
  /// Events handled since construction.
  [[nodiscard]] uint64_t events_processed() const { return m_events; }
  /// Time of the next event (+infinity when none).
  [[nodiscard]] double next_event_time() const;

  /// What an owner may do while the queue works (the default: nothing): before_pop(key, payload)
  /// runs for each event before it is popped, after_pop(queue) after the pop while the next event
  /// is at the top (the queue not empty). An owner whose events touch memory far apart (the
  /// kinetic grid's bands) starts those fetches there, so that they overlap the queue's own work.
  struct NoPrefetch {
    void before_pop(const EventKey&, uint64_t) const {}
    void after_pop(const EventQueue&) const {}
  };

  /// Pops every event with time <= t in (time, kind, a, b) order and calls
  /// handle(const EventKey&, uint64_t payload) for it, with now() = the event time. The event is
  /// already removed from the queue when handle runs. Events scheduled during handling at times
  /// <= t are processed in the same call. Afterwards now() = t. Events earlier than now() and
  /// t < now() are bugs (KINRAY_CHECK).
  template <class F, class P = NoPrefetch>
  void advance_to(double t, F&& handle, const P& prefetch = {}) {
    KINRAY_CHECK_GE(t, m_now);
    while (!m_queue.empty() && m_queue.top_key().time <= t) {
      const EventKey key = m_queue.top_key();
      const uint64_t payload = m_queue.top_payload();
      KINRAY_CHECK_MSG(key.time >= m_now, "event scheduled in the past");
      prefetch.before_pop(key, payload);
      m_queue.pop();
      if (!m_queue.empty()) {
        m_queue.prefetch(m_queue.top());  // overlaps the next slot's miss
        prefetch.after_pop(m_queue);
      }
      m_now = key.time;
      ++m_events;
      handle(key, payload);
    }
    m_now = t;
  }

 private:
  double m_now = 0;
  uint64_t m_events = 0;
  EventQueue m_queue;
};

}  // namespace kinray
