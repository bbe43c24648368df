#pragma once
// How far a long step of a kinetic structure has got (the kinetic grid's initialisation: the
// back-face culling proof over every key, then the scan conversion of every triangle in every
// band). The structure counts, the caller reads from another thread and shows it: the kinetic
// core itself never prints.
#include <atomic>
#include <cstdint>

namespace kinray {

struct WorkProgress {
  std::atomic<const char*> step{nullptr};  ///< the step under way (a string literal), or none
  std::atomic<uint64_t> done{0};
  std::atomic<uint64_t> total{0};  ///< 0 while the step's size is unknown

  /// Starts step `name` of `total_work` units.
  void begin(const char* name, uint64_t total_work) {
    total.store(0, std::memory_order_relaxed);
    done.store(0, std::memory_order_relaxed);
    step.store(name, std::memory_order_relaxed);
    total.store(total_work, std::memory_order_relaxed);
  }
  void add(uint64_t units) { done.fetch_add(units, std::memory_order_relaxed); }

  /// done / total in [0, 1], or a negative number while the total is unknown.
  [[nodiscard]] double fraction() const {
    const uint64_t t = total.load(std::memory_order_relaxed);
    if (t == 0) return -1;
    const uint64_t d = done.load(std::memory_order_relaxed);
    return d >= t ? 1.0 : double(d) / double(t);
  }
};

}  // namespace kinray
