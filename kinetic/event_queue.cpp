#include "kinetic/event_queue.h"

#include <cmath>
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
      m_free(std::exchange(other.m_free, kNoEvent)) {}

EventQueue& EventQueue::operator=(EventQueue&& other) noexcept {
  if (this != &other) {
    std::free(m_heap);
    m_heap = std::exchange(other.m_heap, nullptr);
    m_capacity = std::exchange(other.m_capacity, 0);
    m_size = std::exchange(other.m_size, 0);
    m_slots = std::move(other.m_slots);
    m_pos = std::move(other.m_pos);
    m_free = std::exchange(other.m_free, kNoEvent);
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
  if (m_size == m_capacity) grow(m_capacity < 16 ? 16 : 2 * m_capacity);
  sift_up(m_size++, Node{key.time, h, 0});
  return h;
}

void EventQueue::update(EventHandle h, const EventKey& key) {
  KINRAY_CHECK(contains(h));
  KINRAY_CHECK_MSG(!std::isnan(key.time), "event time is NaN");
  const bool up = key < m_slots[h].key;
  m_slots[h].key = key;
  const uint32_t r = m_pos[h];
  const Node node{key.time, h, 0};
  if (up)
    sift_up(r, node);
  else
    sift_down(r, node);
}

void EventQueue::erase(EventHandle h) {
  KINRAY_CHECK(contains(h));
  remove_at(m_pos[h]);
}

void EventQueue::pop() {
  KINRAY_CHECK(m_size > 0);
  remove_at(0);
}

void EventQueue::remove_at(uint32_t r) {
  const EventHandle h = m_heap[r + kOffset].handle;
  m_pos[h] = kFreeSlot;
  m_slots[h].payload = m_free;
  m_free = h;
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
         m_slots.capacity() * sizeof(Slot) + m_pos.capacity() * sizeof(uint32_t);
}

void EventQueue::audit() const {
  for (uint32_t r = 0; r < m_size; ++r) {
    const Node& node = m_heap[r + kOffset];
    const EventHandle h = node.handle;
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == r);
    KINRAY_CHECK(node.time == m_slots[h].key.time);
    if (r > 0) KINRAY_CHECK(!less(node, m_heap[(r - 1) / kArity + kOffset]));
  }
  size_t free_count = 0;
  for (uint32_t h = m_free; h != kNoEvent; h = static_cast<uint32_t>(m_slots[h].payload)) {
    KINRAY_CHECK(h < m_slots.size() && m_pos[h] == kFreeSlot);
    KINRAY_CHECK(++free_count <= m_slots.size());
  }
  KINRAY_CHECK(free_count + m_size == m_slots.size());
}

}  // namespace kinray
