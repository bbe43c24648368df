#pragma once
// The pixel orders of one band: a kinetic depth order per pixel of its rows (docs/design.md,
// "Depth order per pixel"), the only part of the kinetic grid that depends on the sort
// (--sort list, tournament or heap). The band reaches them through this interface, one virtual
// call per change of a pixel's order; pixel_orders.cpp holds them in one array per sort. Every
// change returns the pixel's front after it, which the band copies into its front array.
//
// The running counts (entries, memory_bytes) are kept by every change, since the band's stats()
// read them after every frame; recount() is the audit's independent check of them.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "kinetic/core/event_queue.h"
#include "kinetic/grid/band_motion.h"
#include "kinetic/sort/depth_sort_kind.h"
#include "kinetic/sort/kinetic_sort.h"

namespace kinray {

/// A pixel's front when no triangle covers it.
inline constexpr uint32_t kNoFront = ~0u;

class PixelOrders {
 public:
  /// The orders of the width * (row_end - row_begin) pixels of rows [row_begin, row_end), by
  /// index (row - row_begin) * width + column. Their swap events go on `queue` with
  /// EventKey{t, event_kind, global pixel index row * width + column, ...}; their counters add up
  /// in `stats`. `motion` and `stats` must outlive the orders.
  [[nodiscard]] static std::unique_ptr<PixelOrders> make(DepthSortKind sort, const BandMotion& motion,
                                                         int width, int row_begin, int row_end,
                                                         EventQueue& queue, uint32_t event_kind,
                                                         KineticSortStats& stats);
  virtual ~PixelOrders() = default;
  PixelOrders(const PixelOrders&) = delete;
  PixelOrders& operator=(const PixelOrders&) = delete;

  // Changes at `now`; each returns the pixel's front after it (kNoFront if empty).
  virtual uint32_t insert(size_t pixel, uint32_t tri, double now) = 0;
  virtual uint32_t erase(size_t pixel, uint32_t tri, double now) = 0;
  /// `from` leaves the pixel and `to` enters it at now (a boundary crossed the pixel's centre:
  /// the two triangles share the edge, and meet the ray at one depth there): erase then insert,
  /// with the same certificates and events, but done in place where `from` is the only member
  /// (most pixels of a closed surface: no certificate) or one of two (a folded sheet: the pair's
  /// event moves). The front after both.
  virtual uint32_t hand_over(size_t pixel, uint32_t from, uint32_t to, double now) = 0;
  /// The motions of the members whose mesh is marked in `switched` changed at now (a flightplan
  /// update): the certificates they take part in are computed afresh, each once.
  virtual uint32_t replace_motions(size_t pixel, const std::vector<uint8_t>& switched,
                                   double now) = 0;
  /// The pixel's swap event with this payload was popped at now.
  virtual uint32_t handle_event(size_t pixel, uint64_t payload, double now) = 0;

  [[nodiscard]] virtual uint32_t front(size_t pixel) const = 0;
  [[nodiscard]] virtual size_t size(size_t pixel) const = 0;
  [[nodiscard]] virtual bool contains(size_t pixel, uint32_t tri) const = 0;
  /// The pixel's triangles into `out` (cleared first): front to back for the sorted list, the
  /// front first but otherwise unsorted for the tournament and the heap.
  virtual void members(size_t pixel, std::vector<uint32_t>& out) const = 0;
  /// The order's own audit at t (KineticSort::audit_problem), without the pixel's context.
  [[nodiscard]] virtual std::optional<std::string> audit_problem(size_t pixel, double t) const = 0;
  /// Entries and bytes counted afresh from every order.
  virtual void recount(uint64_t& entries, size_t& bytes) const = 0;

  /// Starts fetching a pixel's order into the cache (the event loop's prefetch).
  void prefetch(size_t pixel) const { __builtin_prefetch(m_cells + pixel * m_cell_bytes); }
  /// Triangles held, summed over the pixels.
  [[nodiscard]] uint64_t entries() const { return m_entries; }
  /// Bytes of the orders and their keys.
  [[nodiscard]] size_t memory_bytes() const { return m_bytes; }

 protected:
  PixelOrders() = default;
  const std::byte* m_cells = nullptr;  ///< the first pixel's order, for prefetch
  size_t m_cell_bytes = 0;             ///< the stride between two pixels' orders
  uint64_t m_entries = 0;
  size_t m_bytes = 0;
};

}  // namespace kinray
