#include "kinetic/event_queue.h"

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
      m_slots(std::move(other.m_slots)),
      m_pos(std::move(other.m_pos)),
      m_free(std::exchange(other.m_free, kNoEvent)),
      m_far(std::move(other.m_far)),
      m_horizon(std::exchange(other.m_horizon, -std::numeric_limits<double>::infinity())) {}

EventQueue& EventQueue::operator=(EventQueue&& other) noexcept {
  if (this != &other) {
    std::free(m_heap);
    m_heap = std::exchange(other.m_heap, nullptr);
    m_capacity = std::exchange(other.m_capacity, 0);
    m_size = std::exchange(other.m_size, 0);
    m_slots = std::move(other.m_slots);
    m_pos = std::move(other.m_pos);
    m_free = std::exchange(other.m_free, kNoEvent);
    m_far = std::move(other.m_far);
    m_horizon = std::exchange(other.m_horizon, -std::numeric_limits<double>::infinity());
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
  if (key.time > m_horizon) {
    add_far(node);
    settle();
  } else {
    if (m_size == m_capacity) grow(m_capacity < 16 ? 16 : 2 * m_capacity);
    sift_up(m_size++, node);
  }
  return h;
}

void EventQueue::update(EventHandle h, const EventKey& key) {
  KINRAY_CHECK(contains(h));
  KINRAY_CHECK_MSG(!std::isnan(key.time), "event time is NaN");
  const bool up = key < m_slots[h].key;
  m_slots[h].key = key;
  const uint32_t pos = m_pos[h];
  const Node node{key.time, h, uint32_t(m_slots[h].payload)};
  const bool far = key.time > m_horizon;
  if ((pos & kFar) != 0) {
    if (far) {
      m_far[pos & ~kFar].time = key.time;
      return;
    }
    detach_far(pos & ~kFar);
    if (m_size == m_capacity) grow(m_capacity < 16 ? 16 : 2 * m_capacity);
    sift_up(m_size++, node);
    return;
  }
  if (far) {
    detach_heap(pos);
    add_far(node);
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
    detach_far(pos & ~kFar);
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

void EventQueue::detach_far(uint32_t i) {
  const Node last = m_far.back();
  m_far.pop_back();
  if (i == m_far.size()) return;
  m_far[i] = last;
  m_pos[last.handle] = kFar | i;
}

void EventQueue::refill() {
  // The new horizon: a low quantile of a strided sample of the far times (all later than the old
  // horizon, and at least the sampled event itself moves).
  constexpr size_t kSample = 64, kRank = kSample / 8 - 1;
  const size_t n = m_far.size();
  double sample[kSample] = {};
  const size_t count = n < kSample ? n : kSample;
  for (size_t k = 0; k < count; ++k) sample[k] = m_far[k * n / count].time;
  const size_t rank = count < kSample ? 0 : kRank;
  std::nth_element(sample, sample + rank, sample + count);
  m_horizon = sample[rank];
  // Move every far event at or before it to the heap (empty here), then heapify.
  size_t kept = 0;
  for (size_t i = 0; i < n; ++i) {
    const Node node = m_far[i];
    if (node.time <= m_horizon) {
      if (m_size == m_capacity) grow(m_capacity < 16 ? 16 : 2 * m_capacity);
      place(m_size++, node);
    } else {
      m_far[kept] = node;
      m_pos[node.handle] = kFar | uint32_t(kept);
      ++kept;
    }
  }
  m_far.resize(kept);
  if (m_size > 1)
    for (uint32_t r = (m_size - 2) / kArity + 1; r-- > 0;) sift_down(r, m_heap[r + kOffset]);
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
    // Smallest time without branches (random times mispredict), then the rare exact ties.
    uint32_t best = 0;
    double best_time = c[0].time;
    for (uint32_t i = 1; i < count; ++i) {
      const bool smaller = c[i].time < best_time;
      best = smaller ? i : best;
      best_time = smaller ? c[i].time : best_time;
    }
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
  m_far.clear();
  m_horizon = -std::numeric_limits<double>::infinity();
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
         m_far.capacity() * sizeof(Node);
}

void EventQueue::audit() const {
  for (uint32_t r = 0; r < m_size; ++r) {
    const Node& node = m_heap[r + kOffset];
    const EventHandle h = node.handle;
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == r);
    KINRAY_CHECK(node.time == m_slots[h].key.time);
    KINRAY_CHECK(node.hint == uint32_t(m_slots[h].payload));
    if (r > 0) KINRAY_CHECK(!less(node, m_heap[(r - 1) / kArity + kOffset]));
    KINRAY_CHECK(node.time <= m_horizon);
  }
  KINRAY_CHECK(m_size > 0 || m_far.empty());
  for (uint32_t i = 0; i < m_far.size(); ++i) {
    const Node& node = m_far[i];
    const EventHandle h = node.handle;
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == (kFar | i));
    KINRAY_CHECK(node.time == m_slots[h].key.time);
    KINRAY_CHECK(node.hint == uint32_t(m_slots[h].payload));
    KINRAY_CHECK(node.time > m_horizon);
  }
  size_t free_count = 0;
  for (uint32_t h = m_free; h != kNoEvent; h = static_cast<uint32_t>(m_slots[h].payload)) {
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == kFreeSlot);
    KINRAY_CHECK(++free_count <= m_slots.size());
  }
  KINRAY_CHECK(free_count + m_size + m_far.size() == m_slots.size());
}

}  // namespace kinray
