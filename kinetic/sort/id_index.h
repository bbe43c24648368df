#pragma once
// The id -> position index of the kinetic tournament and heap (detail::IdIndex).
#include <bit>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "util/check.h"

namespace kinray {
namespace detail {

/// id -> position for the larger instances of the tournament and heap: open addressing with
/// linear probing (load <= 1/2), backward-shift deletion; one flat array, no nodes. The id ~0u is
/// reserved.
class IdIndex {
 public:
  static constexpr uint32_t kMissing = ~0u;

  [[nodiscard]] uint32_t find(uint32_t id) const {
    if (m_table.empty()) return kMissing;
    for (size_t i = home(id);; i = (i + 1) & mask()) {
      if (m_table[i].id == id) return m_table[i].pos;
      if (m_table[i].id == kEmpty) return kMissing;
    }
  }
  [[nodiscard]] bool contains(uint32_t id) const { return find(id) != kMissing; }
  void set(uint32_t id, uint32_t pos) {
    KINRAY_DCHECK(id != kEmpty);
    if (2 * (m_size + 1) > m_table.size()) rehash(m_table.empty() ? 16 : 2 * m_table.size());
    size_t i = home(id);
    while (m_table[i].id != kEmpty && m_table[i].id != id) i = (i + 1) & mask();
    if (m_table[i].id == kEmpty) ++m_size;
    m_table[i] = {id, pos};
  }
  void erase(uint32_t id) {
    if (m_table.empty()) return;
    size_t i = home(id);
    while (m_table[i].id != id) {
      if (m_table[i].id == kEmpty) return;
      i = (i + 1) & mask();
    }
    // Backward shift: move later entries of the probe run into the hole when allowed.
    for (size_t j = (i + 1) & mask(); m_table[j].id != kEmpty; j = (j + 1) & mask()) {
      const size_t k = home(m_table[j].id);
      const bool movable = i <= j ? (k <= i || k > j) : (k <= i && k > j);
      if (movable) {
        m_table[i] = m_table[j];
        i = j;
      }
    }
    m_table[i].id = kEmpty;
    --m_size;
  }
  void clear() {
    m_table.clear();
    m_size = 0;
  }
  [[nodiscard]] size_t size() const { return m_size; }
  [[nodiscard]] size_t memory_bytes() const { return m_table.capacity() * sizeof(Entry); }

 private:
  static constexpr uint32_t kEmpty = ~0u;
  struct Entry {
    uint32_t id = kEmpty;
    uint32_t pos = 0;
  };
  size_t mask() const { return m_table.size() - 1; }
  size_t home(uint32_t id) const {
    return static_cast<size_t>((uint64_t{id} * 0x9E3779B97F4A7C15ull) >> m_shift);
  }
  void rehash(size_t capacity) {
    std::vector<Entry> old = std::move(m_table);
    m_table.assign(capacity, Entry{});
    m_shift = 64 - std::countr_zero(capacity);
    m_size = 0;
    for (const Entry& e : old)
      if (e.id != kEmpty) set(e.id, e.pos);
  }
  std::vector<Entry> m_table;
  size_t m_size = 0;
  int m_shift = 64;
};

}  // namespace detail
}  // namespace kinray
