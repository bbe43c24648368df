#pragma once
// The calendar of an EventQueue: the events later than the ones in its heap, kept unsorted in
// buckets of equal width in time (a calendar queue, Brown 1988), plus one overflow bucket for
// everything past the calendar's end.
//
// The bucket of a time is floor((t - base) / width), computed as (t - base) * scale in double:
// both roundings are monotone, so an earlier time never lands in a later bucket, and equal times
// always land in the same one. The queue keeps the events of every bucket up to the current one
// in its heap: then every heap event is earlier than every bucket event (their buckets differ),
// and the heap's order, total on (time, kind, ids), is the queue's order. When the heap runs dry
// the next non-empty bucket is heapified (a handful of events); when the calendar runs out, a new
// one is laid over the earlier half of the overflow (its median from a sample), with about
// kTargetSize events per bucket. A push, update or erase outside the heap is O(1), a pop is a
// sift through a heap of about kTargetSize events, and each event is moved about twice from the
// overflow on average: O(1) per event for dense streams, whatever the queue's size.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace kinray {

/// One queue entry: 16 bytes, the handle's full key consulted only for ties in time.
struct QueueNode {
  double time;
  uint32_t handle;
  uint32_t hint;  ///< the payload's low 32 bits, readable at the top without the slot
};

class TimeBuckets {
 public:
  /// Events per bucket a new calendar aims at.
  static constexpr double kTargetSize = 4;
  /// which(): the event belongs in the heap.
  static constexpr int kHeap = -1;

  /// Where an event at time t belongs: kHeap (its bucket is the current one or earlier), a
  /// calendar bucket, or overflow() (past the calendar, or no calendar yet).
  [[nodiscard]] int which(double t) const {
    const int k = raw(t);
    return k <= m_current ? kHeap : k;
  }
  /// The index of the overflow bucket (one past the calendar's).
  [[nodiscard]] int overflow() const { return m_count; }
  /// Bucket k (0 .. overflow()), unsorted; the queue keeps the handles' positions in it.
  [[nodiscard]] std::vector<QueueNode>& operator[](int k) { return m_buckets[size_t(k)]; }
  [[nodiscard]] const std::vector<QueueNode>& operator[](int k) const { return m_buckets[size_t(k)]; }
  /// Events in the buckets and the overflow.
  [[nodiscard]] size_t size() const { return m_size; }
  /// Bookkeeping of size() by the queue, which adds and removes the nodes itself.
  void added(size_t n = 1) { m_size += n; }
  void removed(size_t n = 1) { m_size -= n; }

  /// The next non-empty calendar bucket becomes the current one; its index, or kHeap when the
  /// calendar has none left (then only the overflow holds events).
  int advance() {
    while (++m_current < m_count)
      if (!m_buckets[size_t(m_current)].empty()) return m_current;
    m_current = m_count;
    return kHeap;
  }
  /// Ends the calendar early (the queue has moved every bucket's nodes to the overflow).
  void close() { m_current = m_count; }
  /// The calendar was laid over fewer than half the events it holds now, so its buckets hold
  /// more than twice kTargetSize on average: the queue lays a new one (a queue filled by many
  /// pushes after its first calendar, which a single event or an early rebalance laid).
  /// Re-laying only after the events have doubled keeps its O(n) cost O(1) per event.
  [[nodiscard]] bool stale() const { return m_size > 2 * m_laid_over + kStaleSlack; }
  /// A new calendar over the overflow (every calendar bucket empty): returns the overflow's old
  /// nodes, which the caller places again with which() (into the new buckets or the overflow,
  /// calling added() for each).
  std::vector<QueueNode>& relay() {
    const size_t old_overflow = size_t(m_count);
    m_scratch.clear();
    m_scratch.swap(m_buckets[old_overflow]);
    const std::vector<QueueNode>& nodes = m_scratch;
    const size_t n = nodes.size();
    // The base is the earliest time (its bucket, 0, is never empty); the end is the median of
    // a strided sample, so half the overflow, about, is spread over the new buckets.
    double base = nodes.empty() ? 0 : nodes[0].time;
    for (const QueueNode& node : nodes) base = std::min(base, node.time);
    constexpr size_t kSample = 63;
    double sample[kSample] = {};
    const size_t count = std::min(n, kSample);
    for (size_t k = 0; k < count; ++k) sample[k] = nodes[k * n / count].time;
    std::nth_element(sample, sample + count / 2, sample + count);
    const double end = count == 0 ? base : sample[count / 2];
    const double buckets = std::floor(std::clamp(double(n) / (2 * kTargetSize), 1.0, 65536.0));
    double scale = buckets / (end - base);
    // Every event at one time (or a span too short for double): one bucket holds those up to
    // the end.
    if (!(end > base) || !std::isfinite(scale)) scale = 0;
    m_base = base;
    m_end = end;
    m_scale = scale;
    m_count = int(buckets);
    m_current = -1;
    // Every bucket is empty here. They are kept, beyond the count too, with the capacity of a
    // bucket of the size aimed at: a calendar of fewer buckets that destroyed them made the next
    // larger one allocate them all again, and growing them node by node was 1.8% of all the
    // instructions of an event. Larger ones (a stale calendar's) are released, but for the new
    // overflow, which takes the old one's spare list (the scratch list of the relay before),
    // room for about the half of the nodes it gets back. memory_bytes counts what is kept.
    if (m_buckets.size() < size_t(m_count) + 1) m_buckets.resize(size_t(m_count) + 1);
    std::swap(m_buckets[old_overflow], m_buckets[size_t(m_count)]);
    for (size_t k = 0; k < m_buckets.size(); ++k)
      if (k != size_t(m_count) && m_buckets[k].capacity() > kKeptCapacity)
        std::vector<QueueNode>().swap(m_buckets[k]);
    m_size -= n;
    m_laid_over = n;
    return m_scratch;
  }

  /// No calendar and no events (the state of a new queue).
  void clear() {
    for (auto& b : m_buckets) b.clear();
    m_buckets.resize(1);
    m_count = 0;
    m_current = -1;
    m_size = 0;
    m_laid_over = 0;
    m_base = 0;
    m_scale = 0;
    m_end = -std::numeric_limits<double>::infinity();
  }
  /// Heap memory of the buckets and the scratch list.
  [[nodiscard]] size_t memory_bytes() const {
    size_t bytes = m_buckets.capacity() * sizeof(std::vector<QueueNode>) +
                   m_scratch.capacity() * sizeof(QueueNode);
    for (const auto& b : m_buckets) bytes += b.capacity() * sizeof(QueueNode);
    return bytes;
  }
  /// The last bucket moved to the heap (-1: none yet; count(): the calendar is used up), and
  /// the number of calendar buckets: for EventQueue::audit.
  [[nodiscard]] int current() const { return m_current; }
  [[nodiscard]] int count() const { return m_count; }
  /// The bucket of t before the comparison with the current one (overflow() past the end).
  [[nodiscard]] int raw(double t) const {
    // Past the calendar's end, or the bucket index rounded up to the count there: the overflow.
    // (t > m_end first: a calendar of zero width has a zero scale.)
    if (!(t <= m_end)) return m_count;
    // The base's own bucket is 0 even where the arithmetic has no answer (an infinite base).
    if (t <= m_base) return t < m_base ? -1 : 0;
    const double x = (t - m_base) * m_scale;
    if (!(x < double(m_count))) return m_count;
    return int(x);
  }

 private:
  double m_base = 0, m_scale = 0;
  double m_end = -std::numeric_limits<double>::infinity();  ///< the calendar's last time
  int m_count = 0;     ///< calendar buckets; m_buckets[m_count] is the overflow
  int m_current = -1;  ///< the last bucket moved to the heap
  size_t m_size = 0;
  size_t m_laid_over = 0;  ///< the events of the last relay
  /// Nodes a bucket keeps room for across calendars.
  static constexpr size_t kKeptCapacity = 4 * size_t(kTargetSize);
  /// stale() ignores a calendar's growth by this many events (small queues keep theirs).
  static constexpr size_t kStaleSlack = 1024;
  std::vector<std::vector<QueueNode>> m_buckets = std::vector<std::vector<QueueNode>>(1);
  std::vector<QueueNode> m_scratch;
};

}  // namespace kinray
