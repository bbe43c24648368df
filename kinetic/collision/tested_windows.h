#pragma once
// Per triangle pair, the time up to which the kinetic separation list has tested it on the
// current segment: a small open-addressing table cleared at every segment. The list looks a pair
// up at every test (every listed pair at every segment start, some thousands), which a node-based
// std::unordered_map paid for with an allocation per pair and a free per pair at each clear.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace kinray {

class TestedWindows {
 public:
  /// The pair's entry, inserted with `until` when absent (then `inserted`).
  struct Slot {
    double* until;
    bool inserted;
  };
  Slot try_emplace(uint64_t pair, double until) {
    if (2 * (m_size + 1) > m_keys.size()) grow();
    size_t i = index(pair);
    while (m_keys[i] != kEmpty) {
      if (m_keys[i] == pair) return {&m_until[i], false};
      i = (i + 1) & (m_keys.size() - 1);
    }
    m_keys[i] = pair;
    m_until[i] = until;
    ++m_size;
    return {&m_until[i], true};
  }
  /// The time up to which the pair was tested, or nullptr when it was not on this segment.
  [[nodiscard]] const double* find(uint64_t pair) const {
    if (m_keys.empty()) return nullptr;
    for (size_t i = index(pair); m_keys[i] != kEmpty; i = (i + 1) & (m_keys.size() - 1))
      if (m_keys[i] == pair) return &m_until[i];
    return nullptr;
  }
  void clear() {
    if (m_size == 0) return;
    std::fill(m_keys.begin(), m_keys.end(), kEmpty);
    m_size = 0;
  }

 private:
  static constexpr uint64_t kEmpty = ~uint64_t(0);  // no triangle pair: ids are below 2^32 - 1
  [[nodiscard]] size_t index(uint64_t pair) const {
    return size_t((pair * 0x9E3779B97F4A7C15ull) >> 32) & (m_keys.size() - 1);
  }
  void grow() {
    std::vector<uint64_t> keys(m_keys.empty() ? 1024 : 2 * m_keys.size(), kEmpty);
    std::vector<double> until(keys.size());
    keys.swap(m_keys);
    until.swap(m_until);
    m_size = 0;
    for (size_t i = 0; i < keys.size(); ++i)
      if (keys[i] != kEmpty) *try_emplace(keys[i], until[i]).until = until[i];
  }

  std::vector<uint64_t> m_keys;
  std::vector<double> m_until;
  size_t m_size = 0;
};

}  // namespace kinray
