#include "kinetic/core/event_queue.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <cstdlib>
#include <cstring>
#include <new>
#include <utility>

namespace kinray {

namespace {
constexpr uint32_t kArity = EventQueue::kArity;
constexpr size_t kAlign = 128;
}  // namespace

EventQueue::EventQueue(EventQueue&& other) noexcept
    : m_heap(std::exchange(other.m_heap, nullptr)),
      m_capacity(std::exchange(other.m_capacity, 0)),
      m_size(std::exchange(other.m_size, 0)),
      m_heap_laid(std::exchange(other.m_heap_laid, 0)),
      m_slots(std::move(other.m_slots)),
      m_pos(std::move(other.m_pos)),
      m_free(std::exchange(other.m_free, kNoEvent)),
      m_far(std::move(other.m_far)) {
  other.m_far.clear();
}

EventQueue& EventQueue::operator=(EventQueue&& other) noexcept {
  if (this != &other) {
    std::free(m_heap);
    m_heap = std::exchange(other.m_heap, nullptr);
    m_capacity = std::exchange(other.m_capacity, 0);
    m_size = std::exchange(other.m_size, 0);
    m_heap_laid = std::exchange(other.m_heap_laid, 0);
    m_slots = std::move(other.m_slots);
    m_pos = std::move(other.m_pos);
    m_free = std::exchange(other.m_free, kNoEvent);
    m_far = std::move(other.m_far);
    other.m_far.clear();
  }
  return *this;
}

EventQueue::~EventQueue() { std::free(m_heap); }

void EventQueue::grow(size_t capacity) {
  if (capacity <= m_capacity) return;
  const size_t bytes = ((capacity + kOffset + 1) * sizeof(Node) + kAlign - 1) / kAlign * kAlign;
  auto* heap = static_cast<Node*>(std::aligned_alloc(kAlign, bytes));
  if (!heap) throw std::bad_alloc();
  if (m_heap) std::memcpy(heap, m_heap, (m_size + kOffset) * sizeof(Node));
  std::free(m_heap);
  m_heap = heap;
  m_capacity = capacity;
}

EventHandle EventQueue::push(const EventKey& key, uint64_t payload) {
  KINRAY_CHECK_MSG(!std::isnan(key.time), "event time is NaN");
  EventHandle h;
  if (m_free != kNoEvent) {
    h = m_free;
    m_free = static_cast<uint32_t>(m_slots[h].payload);
  } else {
    KINRAY_CHECK(m_slots.size() < kNoEvent - 1);
    h = static_cast<EventHandle>(m_slots.size());
    m_slots.emplace_back();
    m_pos.push_back(kFreeSlot);
  }
  m_slots[h].key = key;
  m_slots[h].payload = payload;
  const Node node{key.time, h, uint32_t(payload)};
  const int k = m_far.which(key.time);
  if (k == TimeBuckets::kHeap) {
    add_heap(node);
  } else {
    add_far(k, node);
    settle();
  }
  return h;
}

void EventQueue::update(EventHandle h, const EventKey& key) {
  KINRAY_CHECK(contains(h));
  KINRAY_CHECK_MSG(!std::isnan(key.time), "event time is NaN");
  const double old_time = m_slots[h].key.time;
  const bool up = key < m_slots[h].key;
  m_slots[h].key = key;
  const uint32_t pos = m_pos[h];
  const Node node{key.time, h, uint32_t(m_slots[h].payload)};
  const int k = m_far.which(key.time);
  if ((pos & kFar) != 0) {
    const int old_k = m_far.raw(old_time);
    if (k == old_k) {
      m_far[k][pos & ~kFar].time = key.time;
      return;
    }
    detach_far(old_k, pos & ~kFar);
    if (k == TimeBuckets::kHeap)
      add_heap(node);
    else
      add_far(k, node);
    return;
  }
  if (k != TimeBuckets::kHeap) {
    detach_heap(pos);
    add_far(k, node);
    settle();
  } else if (up) {
    sift_up(pos, node);
  } else {
    sift_down(pos, node);
  }
}

void EventQueue::erase(EventHandle h) {
  KINRAY_CHECK(contains(h));
  const uint32_t pos = m_pos[h];
  if ((pos & kFar) != 0)
    detach_far(m_far.raw(m_slots[h].key.time), pos & ~kFar);
  else
    detach_heap(pos);
  free_handle(h);
  settle();
}

void EventQueue::pop() {
  KINRAY_CHECK(m_size > 0);
  const EventHandle h = m_heap[kOffset].handle;
  detach_heap(0);
  free_handle(h);
  settle();
}

void EventQueue::detach_far(int k, uint32_t i) {
  std::vector<Node>& bucket = m_far[k];
  const Node last = bucket.back();
  bucket.pop_back();
  m_far.removed();
  if (i == bucket.size()) return;
  bucket[i] = last;
  m_pos[last.handle] = kFar | i;
}

void EventQueue::refill() {
  // A calendar laid over far fewer events than it holds now is replaced: its buckets would be
  // heaps of hundreds of events (rebalance() comes back here with the calendar closed).
  if (m_far.current() < m_far.count() && m_far.stale()) {
    rebalance();
    return;
  }
  // The next non-empty bucket, or a new calendar over the overflow (whose bucket 0, holding its
  // earliest event, is never empty).
  int k = m_far.advance();
  if (k == TimeBuckets::kHeap) {
    for (const Node& node : m_far.relay()) {
      const int b = m_far.which(node.time);
      KINRAY_DCHECK(b != TimeBuckets::kHeap);
      add_far(b, node);
    }
    k = m_far.advance();
    KINRAY_CHECK(k != TimeBuckets::kHeap);
  }
  // Its events go to the heap (empty here), which is then heapified.
  std::vector<Node>& bucket = m_far[k];
  if (m_size + bucket.size() > m_capacity) grow(std::max<size_t>(16, 2 * (m_size + bucket.size())));
  for (const Node& node : bucket) place(m_size++, node);
  m_heap_laid = m_size;
  m_far.removed(bucket.size());
  bucket.clear();
  if (m_size > 1)
    for (uint32_t r = (m_size - 2) / kArity + 1; r-- > 0;) sift_down(r, m_heap[r + kOffset]);
}

void EventQueue::rebalance() {
  // The nodes are appended to the overflow as they are: the relay in refill() places every one
  // of them again and writes its position then.
  std::vector<Node>& overflow = m_far[m_far.overflow()];
  overflow.insert(overflow.end(), m_heap + kOffset, m_heap + kOffset + m_size);
  m_far.added(m_size);
  m_size = 0;
  for (int k = std::max(m_far.current() + 1, 0); k < m_far.overflow(); ++k) {
    overflow.insert(overflow.end(), m_far[k].begin(), m_far[k].end());
    m_far[k].clear();
  }
  m_far.close();
  refill();
}

void EventQueue::detach_heap(uint32_t r) {
  const uint32_t last = --m_size;
  if (r == last) return;
  const Node moved = m_heap[last + kOffset];
  if (r > 0 && less(moved, m_heap[(r - 1) / kArity + kOffset]))
    sift_up(r, moved);
  else
    sift_down(r, moved);
}

void EventQueue::sift_up(uint32_t r, Node node) {
  while (r > 0) {
    const uint32_t parent = (r - 1) / kArity;
    const Node& p = m_heap[parent + kOffset];
    if (!less(node, p)) break;
    place(r, p);
    r = parent;
  }
  place(r, node);
}

void EventQueue::sift_down(uint32_t r, Node node) {
  const uint32_t n = m_size;
  for (;;) {
    const uint32_t first = r * kArity + 1;
    if (first >= n) break;
    const Node* c = m_heap + first + kOffset;
    const uint32_t count = n - first < kArity ? n - first : kArity;
    // Smallest time without branches (random times mispredict), then the rare exact ties. A
    // child before the first smallest is later than it, so a tie can only follow it: `tie`
    // notes one on the way, and the keys are compared only then.
    uint32_t best = 0;
    double best_time = c[0].time;
    bool tie = false;
    for (uint32_t i = 1; i < count; ++i) {
      const bool smaller = c[i].time < best_time;
      tie = (!smaller) & (tie | (c[i].time == best_time));
      best = smaller ? i : best;
      best_time = smaller ? c[i].time : best_time;
    }
    if (tie) [[unlikely]]
      for (uint32_t i = 0; i < count; ++i)
        if (c[i].time == best_time && i != best && less(c[i], c[best])) best = i;
    if (!less(c[best], node)) break;
    place(r, c[best]);
    r = first + best;
  }
  place(r, node);
}

void EventQueue::clear() {
  m_size = 0;
  m_heap_laid = 0;
  m_far.clear();
  m_slots.clear();
  m_pos.clear();
  m_free = kNoEvent;
}

void EventQueue::reserve(size_t n) {
  grow(n);
  m_slots.reserve(n);
  m_pos.reserve(n);
}

size_t EventQueue::memory_bytes() const {
  return sizeof(*this) + (m_capacity + kOffset + 1) * sizeof(Node) +
         m_slots.capacity() * sizeof(Slot) + m_pos.capacity() * sizeof(uint32_t) +
         m_far.memory_bytes();
}

void EventQueue::audit() const {
  for (uint32_t r = 0; r < m_size; ++r) {
    const Node& node = m_heap[r + kOffset];
    const EventHandle h = node.handle;
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == r);
    KINRAY_CHECK(node.time == m_slots[h].key.time);
    KINRAY_CHECK(node.hint == uint32_t(m_slots[h].payload));
    if (r > 0) KINRAY_CHECK(!less(node, m_heap[(r - 1) / kArity + kOffset]));
    // Before every bucket event: in the current bucket or earlier.
    KINRAY_CHECK(m_far.raw(node.time) <= m_far.current());
  }
  KINRAY_CHECK(m_size > 0 || m_far.size() == 0);
  size_t far_count = 0;
  for (int k = 0; k <= m_far.overflow(); ++k) {
    KINRAY_CHECK(m_far[k].empty() || k > m_far.current());
    for (uint32_t i = 0; i < m_far[k].size(); ++i) {
      const Node& node = m_far[k][i];
      const EventHandle h = node.handle;
      KINRAY_CHECK(h < m_slots.size() && m_pos[h] == (kFar | i));
      KINRAY_CHECK(node.time == m_slots[h].key.time);
      KINRAY_CHECK(node.hint == uint32_t(m_slots[h].payload));
      KINRAY_CHECK(m_far.raw(node.time) == k);
      ++far_count;
    }
  }
  KINRAY_CHECK(far_count == m_far.size());
  size_t free_count = 0;
  for (uint32_t h = m_free; h != kNoEvent; h = static_cast<uint32_t>(m_slots[h].payload)) {
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == kFreeSlot);
    KINRAY_CHECK(++free_count <= m_slots.size());
  }
  KINRAY_CHECK(free_count + m_size + far_count == m_slots.size());
}

}  // namespace kinray
