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
  [[nodiscard]] EventQueue& queue() { return m_queue; }
  [[nodiscard]] const EventQueue& queue() const { return m_queue; }
  /// Events handled since construction.
  [[nodiscard]] uint64_t events_processed() const { return m_events; }
  /// Time of the next event (+infinity when none).
  [[nodiscard]] double next_event_time() const;

  /// Pops every event with time <= t in (time, kind, a, b) order and calls
  /// handle(const EventKey&, uint64_t payload) for it, with now() = the event time. The event is
  /// already removed from the queue when handle runs. Events scheduled during handling at times
  /// <= t are processed in the same call. Afterwards now() = t. Events earlier than now() and
  /// t < now() are bugs (KINRAY_CHECK).
  template <class F>
  void advance_to(double t, F&& handle) {
    KINRAY_CHECK_GE(t, m_now);
    while (!m_queue.empty() && m_queue.top_key().time <= t) {
      const EventKey key = m_queue.top_key();
      const uint64_t payload = m_queue.top_payload();
      KINRAY_CHECK_MSG(key.time >= m_now, "event scheduled in the past");
      m_queue.pop();
      if (!m_queue.empty()) m_queue.prefetch(m_queue.top());  // overlaps the next slot's miss
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
