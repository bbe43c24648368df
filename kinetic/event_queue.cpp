#include "kinetic/event_queue.h"

#include <cmath>

namespace kinray {

namespace {
constexpr uint32_t kArity = 4;
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
  }
  const auto pos = static_cast<uint32_t>(m_heap.size());
  m_heap.push_back({key, h});
  m_slots[h] = {payload, pos};
  sift_up(pos);
  return h;
}

void EventQueue::update(EventHandle h, const EventKey& key) {
  KINRAY_CHECK(contains(h));
  KINRAY_CHECK_MSG(!std::isnan(key.time), "event time is NaN");
  const uint32_t pos = m_slots[h].pos;
  const bool up = key < m_heap[pos].key;
  m_heap[pos].key = key;
  if (up)
    sift_up(pos);
  else
    sift_down(pos);
}

void EventQueue::erase(EventHandle h) {
  KINRAY_CHECK(contains(h));
  remove_at(m_slots[h].pos);
}

void EventQueue::set_payload(EventHandle h, uint64_t payload) {
  KINRAY_DCHECK(contains(h));
  m_slots[h].payload = payload;
}

void EventQueue::pop() {
  KINRAY_CHECK(!m_heap.empty());
  remove_at(0);
}

void EventQueue::remove_at(uint32_t pos) {
  const EventHandle h = m_heap[pos].handle;
  m_slots[h].pos = kFreeSlot;
  m_slots[h].payload = m_free;
  m_free = h;
  const auto last = static_cast<uint32_t>(m_heap.size() - 1);
  if (pos != last) {
    const bool up = m_heap[last].key < m_heap[pos].key;
    m_heap[pos] = m_heap[last];
    m_slots[m_heap[pos].handle].pos = pos;
    m_heap.pop_back();
    if (up)
      sift_up(pos);
    else
      sift_down(pos);
  } else {
    m_heap.pop_back();
  }
}

void EventQueue::sift_up(uint32_t pos) {
  const Node node = m_heap[pos];
  while (pos > 0) {
    const uint32_t parent = (pos - 1) / kArity;
    if (!(node.key < m_heap[parent].key)) break;
    m_heap[pos] = m_heap[parent];
    m_slots[m_heap[pos].handle].pos = pos;
    pos = parent;
  }
  m_heap[pos] = node;
  m_slots[node.handle].pos = pos;
}

void EventQueue::sift_down(uint32_t pos) {
  const Node node = m_heap[pos];
  const auto n = static_cast<uint32_t>(m_heap.size());
  for (;;) {
    const uint32_t first = pos * kArity + 1;
    if (first >= n) break;
    uint32_t best = first;
    const uint32_t end = first + kArity < n ? first + kArity : n;
    for (uint32_t c = first + 1; c < end; ++c)
      if (m_heap[c].key < m_heap[best].key) best = c;
    if (!(m_heap[best].key < node.key)) break;
    m_heap[pos] = m_heap[best];
    m_slots[m_heap[pos].handle].pos = pos;
    pos = best;
  }
  m_heap[pos] = node;
  m_slots[node.handle].pos = pos;
}

void EventQueue::clear() {
  m_heap.clear();
  m_slots.clear();
  m_free = kNoEvent;
}

void EventQueue::reserve(size_t n) {
  m_heap.reserve(n);
  m_slots.reserve(n);
}

size_t EventQueue::memory_bytes() const {
  return sizeof(*this) + m_heap.capacity() * sizeof(Node) + m_slots.capacity() * sizeof(Slot);
}

void EventQueue::audit() const {
  for (uint32_t pos = 0; pos < m_heap.size(); ++pos) {
    const EventHandle h = m_heap[pos].handle;
    KINRAY_CHECK(h < m_slots.size() && m_slots[h].pos == pos);
    if (pos > 0) KINRAY_CHECK(!(m_heap[pos].key < m_heap[(pos - 1) / kArity].key));
  }
  size_t free_count = 0;
  for (uint32_t h = m_free; h != kNoEvent; h = static_cast<uint32_t>(m_slots[h].payload)) {
    KINRAY_CHECK(h < m_slots.size() && m_slots[h].pos == kFreeSlot);
    KINRAY_CHECK(++free_count <= m_slots.size());
  }
  KINRAY_CHECK(free_count + m_heap.size() == m_slots.size());
}

}  // namespace kinray
