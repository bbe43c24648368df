#pragma once
// An addressable 4-ary min-heap of events with stable handles.

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kinetic/check.h"

namespace kinray {

/// Deterministic order for equal times: (time, kind, a, b) lexicographic.
struct EventKey {
  double time = 0;
  uint32_t kind = 0;
  uint32_t a = 0;
  uint64_t b = 0;
};

inline bool operator<(const EventKey& x, const EventKey& y) {
  if (x.time != y.time) return x.time < y.time;
  if (x.kind != y.kind) return x.kind < y.kind;
  if (x.a != y.a) return x.a < y.a;
  return x.b < y.b;
}
inline bool operator==(const EventKey& x, const EventKey& y) {
  return x.time == y.time && x.kind == y.kind && x.a == y.a && x.b == y.b;
}

using EventHandle = uint32_t;  ///< stable until erase / pop of that event
inline constexpr EventHandle kNoEvent = ~0u;

/// Event queue shared by many kinetic structures. Handles of popped or erased events are
/// recycled by later pushes.
class EventQueue {
 public:
  EventHandle push(const EventKey& key, uint64_t payload);  ///< O(log n)
  void update(EventHandle h, const EventKey& key);          ///< O(log n), either direction
  void erase(EventHandle h);                                ///< O(log n)
  void set_payload(EventHandle h, uint64_t payload);        ///< O(1)

  [[nodiscard]] bool empty() const { return m_heap.empty(); }
  [[nodiscard]] size_t size() const { return m_heap.size(); }
  [[nodiscard]] const EventKey& top_key() const {
    KINRAY_DCHECK(!m_heap.empty());
    return m_heap.front().key;
  }
  [[nodiscard]] uint64_t top_payload() const { return m_slots[top()].payload; }
  [[nodiscard]] EventHandle top() const {
    KINRAY_DCHECK(!m_heap.empty());
    return m_heap.front().handle;
  }
  void pop();  ///< removes the top event; its handle becomes invalid

  [[nodiscard]] const EventKey& key(EventHandle h) const {
    KINRAY_DCHECK(contains(h));
    return m_heap[m_slots[h].pos].key;
  }
  [[nodiscard]] uint64_t payload(EventHandle h) const {
    KINRAY_DCHECK(contains(h));
    return m_slots[h].payload;
  }
  [[nodiscard]] bool contains(EventHandle h) const {
    return h < m_slots.size() && m_slots[h].pos != kFreeSlot;
  }

  void clear();
  void reserve(size_t n);
  [[nodiscard]] size_t memory_bytes() const;
  /// Heap order and handle consistency, O(n) (KINRAY_CHECK); for tests.
  void audit() const;

 private:
  static constexpr uint32_t kFreeSlot = ~0u;
  struct Node {
    EventKey key;
    EventHandle handle;
  };
  struct Slot {
    uint64_t payload = 0;  ///< the event's payload, or the next free slot when free
    uint32_t pos = kFreeSlot;
  };
  void sift_up(uint32_t pos);
  void sift_down(uint32_t pos);
  void remove_at(uint32_t pos);

  std::vector<Node> m_heap;
  std::vector<Slot> m_slots;
  uint32_t m_free = kNoEvent;
};

}  // namespace kinray
