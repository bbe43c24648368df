#pragma once
// An addressable 8-ary min-heap of events with stable handles, over a calendar of time buckets.

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "kinetic/core/time_buckets.h"
#include "util/check.h"

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

/// Event queue shared by many kinetic structures: an 8-ary min-heap of (time, handle) pairs of 16
/// bytes, each group of eight siblings in one aligned pair of cache lines; the full keys and
/// payloads live in a slot per handle (consulted for ties in time only). Handles of popped or
/// erased events are recycled by later pushes.
///
/// Most certificates fail long after the events being processed (a boundary crosses its next
/// column centre frames later), so only the earliest events are kept in the heap: the rest wait
/// unsorted in the time buckets of a calendar (time_buckets.h), where push, update and erase are
/// O(1). When the heap runs dry the next bucket is heapified. The heap holds a handful of events,
/// and the order of the events is exactly that of one heap: every bucket event is later than
/// every heap event.
class EventQueue {
 public:
  EventQueue() = default;
  EventQueue(const EventQueue&) = delete;
  EventQueue& operator=(const EventQueue&) = delete;
  EventQueue(EventQueue&& other) noexcept;
  EventQueue& operator=(EventQueue&& other) noexcept;
  ~EventQueue();

  EventHandle push(const EventKey& key, uint64_t payload);  ///< O(log n)
  void update(EventHandle h, const EventKey& key);          ///< O(log n), either direction
  void erase(EventHandle h);                                ///< O(log n)
  /// The one way every kinetic structure (re)schedules a certificate's event: `handle` is the
  /// structure's own slot for it (kNoEvent when none is pending). A finite key.time pushes the
  /// event or moves the pending one there with the new payload; +inf (never) cancels it.
  void schedule(EventHandle& handle, const EventKey& key, uint64_t payload) {
    if (key.time == std::numeric_limits<double>::infinity()) {
      cancel(handle);
    } else if (handle == kNoEvent) {
      handle = push(key, payload);
    } else {
      update(handle, key);
      set_payload(handle, payload);
    }
  }
  /// Erases the pending event of `handle`, if any, and clears the slot.
  void cancel(EventHandle& handle) {
    if (handle != kNoEvent) erase(handle);
    handle = kNoEvent;
  }
  void set_payload(EventHandle h, uint64_t payload) {       ///< O(1)
    KINRAY_DCHECK(contains(h));
    m_slots[h].payload = payload;
    const uint32_t pos = m_pos[h];
    ((pos & kFar) != 0 ? far_node(h) : m_heap[pos + kOffset]).hint = uint32_t(payload);
  }

  [[nodiscard]] bool empty() const { return m_size == 0 && m_far.size() == 0; }
  [[nodiscard]] size_t size() const { return m_size + m_far.size(); }
  [[nodiscard]] const EventKey& top_key() const { return m_slots[top()].key; }
  [[nodiscard]] uint64_t top_payload() const { return m_slots[top()].payload; }
  /// The low 32 bits of top_payload(), from the heap itself: enough for the owner to prefetch
  /// what the next event will touch while the current one is processed.
  [[nodiscard]] uint32_t top_payload_hint() const {
    KINRAY_DCHECK(m_size > 0);
    return m_heap[kOffset].hint;
  }
  /// The same for the event after the top one, when it is in the heap (the earliest of the top's
  /// children; equal times ordered arbitrarily), else kNoEvent: a guess to prefetch by, two
  /// events ahead.
  [[nodiscard]] uint32_t second_payload_hint() const {
    if (m_size < 2) return kNoEvent;
    const uint32_t children = m_size > kArity ? kArity : m_size - 1;
    const Node* child = m_heap + kOffset + 1;
    uint32_t earliest = 0;
    for (uint32_t i = 1; i < children; ++i)
      if (child[i].time < child[earliest].time) earliest = i;
    return child[earliest].hint;
  }
  [[nodiscard]] EventHandle top() const {
    KINRAY_DCHECK(m_size > 0);  // settle() keeps the heap non-empty while the far list is not
    return m_heap[kOffset].handle;
  }
  void pop();  ///< removes the top event; its handle becomes invalid

  [[nodiscard]] const EventKey& key(EventHandle h) const {
    KINRAY_DCHECK(contains(h));
    return m_slots[h].key;
  }
  [[nodiscard]] uint64_t payload(EventHandle h) const {
    KINRAY_DCHECK(contains(h));
    return m_slots[h].payload;
  }
  [[nodiscard]] bool contains(EventHandle h) const {
    return h < m_pos.size() && m_pos[h] != kFreeSlot;
  }
  /// Hint that event h is about to be updated or erased (software prefetch of its slot).
  void prefetch(EventHandle h) const {
    if (h < m_slots.size()) {
      __builtin_prefetch(&m_slots[h]);
      __builtin_prefetch(&m_pos[h]);
    }
  }

  void clear();
  void reserve(size_t n);
  [[nodiscard]] size_t memory_bytes() const;
  /// Heap order and handle consistency, O(n) (KINRAY_CHECK); for tests.
  void audit() const;

 private:
  static constexpr uint32_t kFreeSlot = ~0u;
  static constexpr uint32_t kFar = 1u << 31;  ///< m_pos bit: the index is into a time bucket
 public:
  static constexpr uint32_t kArity = 8;  ///< children per node

 private:
  // Heap entry r is stored at m_heap[r + kOffset]; the children of r, 8r+1 .. 8r+8, are then
  // stored at 8(r+1) .. 8(r+1)+7: one 128-byte aligned group (two cache lines).
  static constexpr uint32_t kOffset = kArity - 1;
  using Node = QueueNode;
  struct alignas(32) Slot {
    EventKey key;
    uint64_t payload = 0;  ///< the event's payload, or the next free slot when free
  };
  bool less(const Node& x, const Node& y) const {
    if (x.time != y.time) return x.time < y.time;
    return m_slots[x.handle].key < m_slots[y.handle].key;
  }
  void place(uint32_t r, const Node& node) {
    m_heap[r + kOffset] = node;
    m_pos[node.handle] = r;
  }
  void sift_up(uint32_t r, Node node);
  void sift_down(uint32_t r, Node node);
  /// Takes the node at heap index r out of the heap (its handle stays allocated).
  void detach_heap(uint32_t r);
  /// The far node of handle h (in the bucket of its key's time).
  Node& far_node(EventHandle h) {
    return m_far[m_far.raw(m_slots[h].key.time)][m_pos[h] & ~kFar];
  }
  /// Takes the node at index i of bucket k out of it (its handle stays allocated).
  void detach_far(int k, uint32_t i);
  /// Puts a node with a handle into bucket k (not the heap).
  void add_far(int k, const Node& node) {
    std::vector<Node>& bucket = m_far[k];
    m_pos[node.handle] = kFar | uint32_t(bucket.size());
    bucket.push_back(node);
    m_far.added();
  }
  /// Puts a node into the heap; a new calendar when the heap has grown out of proportion.
  void add_heap(const Node& node) {
    if (m_size == m_capacity) grow(m_capacity < 16 ? 16 : 2 * m_capacity);
    sift_up(m_size++, node);
    if (m_size > kLargeHeap && m_size > m_far.size() / 16 && m_size > 2 * m_heap_laid) [[unlikely]]
      rebalance();
  }
  /// Every event back to the overflow and a new calendar from the earliest: for a heap that
  /// the events earlier than the calendar's start have filled (the first calendar is laid over
  /// the first event pushed). It costs O(n) once the heap holds a sixteenth of the events.
  void rebalance();
  static constexpr uint32_t kLargeHeap = 1024;
  void free_handle(EventHandle h) {
    m_pos[h] = kFreeSlot;
    m_slots[h].payload = m_free;
    m_free = h;
  }
  /// Restores "the heap is empty only if the buckets are" by moving to the next bucket.
  void settle() {
    if (m_size == 0 && m_far.size() != 0) refill();
  }
  void refill();
  void grow(size_t capacity);

  Node* m_heap = nullptr;  ///< 64-byte aligned, m_capacity + kOffset + 1 nodes
  size_t m_capacity = 0;
  uint32_t m_size = 0;
  /// The heap's size when its last bucket came in. A rebalance waits until pushes have doubled
  /// it: a bucket of thousands of events at one instant (a keyframe's certificates) fills the
  /// heap beyond a sixteenth of the queue at once, and a new calendar puts them all in its first
  /// bucket again, so rebalancing at the next push, and the next, cost O(n) each.
  uint32_t m_heap_laid = 0;
  std::vector<Slot> m_slots;     ///< per handle: key and payload (two slots per cache line)
  std::vector<uint32_t> m_pos;  ///< per handle: heap index r, kFar | far index, or kFreeSlot
  uint32_t m_free = kNoEvent;
  TimeBuckets m_far;  ///< the events later than the heap's, by time buckets
};

}  // namespace kinray
