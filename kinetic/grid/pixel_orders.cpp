// The pixel orders of a band for each sort: one array of (keys, order) cells, the orders pointing
// at their keys (so the array is built once and never moves).
#include "kinetic/grid/pixel_orders.h"

#include "kinetic/grid/pixel_depth_order.h"
#include "kinetic/sort/kinetic_heap.h"
#include "kinetic/sort/kinetic_sorted_list.h"
#include "kinetic/sort/kinetic_tournament.h"

namespace kinray {

namespace {

template <class Sort>
class PixelOrdersOf final : public PixelOrders {
 public:
  PixelOrdersOf(const BandMotion& motion, int width, int row_begin, int row_end, EventQueue& queue,
                const KineticSortConfig& config)
      : m_motion(&motion) {
    m_cells_of.reserve(size_t(row_end - row_begin) * size_t(width));
    for (int j = row_begin; j < row_end; ++j)
      for (int i = 0; i < width; ++i)
        m_cells_of.emplace_back(&motion, i, j, queue, uint32_t(size_t(j) * size_t(width) + size_t(i)),
                                config);
    m_cells = reinterpret_cast<const std::byte*>(&m_cells_of.front().order);
    m_cell_bytes = sizeof(Cell);
    recount(m_entries, m_bytes);
  }

  uint32_t insert(size_t pixel, uint32_t tri, double now) override {
    ++m_entries;
    return change(pixel, [&](Sort& order) { order.insert(tri, now); });
  }
  uint32_t erase(size_t pixel, uint32_t tri, double now) override {
    --m_entries;
    return change(pixel, [&](Sort& order) { order.erase(tri, now); });
  }
  uint32_t hand_over(size_t pixel, uint32_t from, uint32_t to, double now) override {
    if constexpr (requires(Sort& order) {
                    order.rename_sole(to);
                    order.replace_in_pair(from, to, now);
                    order.replace_in_place(from, to, now);
                  }) {
      // The same bytes and members before and after, but for the one handed over.
      Sort& order = m_cells_of[pixel].order;
      if (order.size() == 1 && order.front() == from) {
        order.rename_sole(to);
        return to;
      }
      if (order.size() == 2 && order.contains(from)) {
        order.replace_in_pair(from, to, now);
        return order.front().value_or(kNoFront);
      }
      // Deeper orders: `to` at `from`'s place when its two neighbours agree (from must be a
      // member, as erase below requires: replace_in_place checks it as erase does).
      if (order.size() > 2 && order.replace_in_place(from, to, now))
        return order.front().value_or(kNoFront);
    }
    erase(pixel, from, now);
    return insert(pixel, to, now);
  }
  uint32_t replace_motions(size_t pixel, const std::vector<uint8_t>& switched,
                           double now) override {
    Sort& order = m_cells_of[pixel].order;
    const GridScene& scene = m_motion->scene();
    const auto moved = [&](uint32_t tri) { return switched[scene.mesh_of_triangle(tri)] != 0; };
    order.replace_motions(moved, now);  // the same members and bytes (the audit's running counts)
    return order.front().value_or(kNoFront);
  }
  uint32_t handle_event(size_t pixel, uint64_t payload, double now) override {
    return change(pixel, [&](Sort& order) { order.handle_event(payload, now); });
  }

  uint32_t front(size_t pixel) const override {
    return m_cells_of[pixel].order.front().value_or(kNoFront);
  }
  size_t size(size_t pixel) const override { return m_cells_of[pixel].order.size(); }
  bool contains(size_t pixel, uint32_t tri) const override {
    return m_cells_of[pixel].order.contains(tri);
  }
  void members(size_t pixel, std::vector<uint32_t>& out) const override {
    out.clear();
    m_cells_of[pixel].order.for_each([&](uint32_t tri) { out.push_back(tri); });
  }
  std::optional<std::string> audit_problem(size_t pixel, double t) const override {
    return m_cells_of[pixel].order.audit_problem(t);
  }
  void recount(uint64_t& entries, size_t& bytes) const override {
    entries = 0;
    bytes = 0;
    for (const Cell& cell : m_cells_of) {
      entries += cell.order.size();
      bytes += cell.order.memory_bytes() + sizeof(PixelDepthKeys);
    }
  }

 private:
  /// Applies a change to the pixel's order, keeping m_bytes (unsigned: the difference wraps
  /// back when the order shrinks); returns its front after it.
  template <class Change>
  uint32_t change(size_t pixel, Change&& apply) {
    Sort& order = m_cells_of[pixel].order;
    const size_t before = order.memory_bytes();
    apply(order);
    m_bytes = m_bytes - before + order.memory_bytes();
    return order.front().value_or(kNoFront);
  }

  struct Cell {
    Cell(const BandMotion* motion, int column, int row, EventQueue& queue, uint32_t owner,
         const KineticSortConfig& config)
        : keys(motion, column, row), order(keys, queue, owner, config) {}
    PixelDepthKeys keys;
    Sort order;
  };
  std::vector<Cell> m_cells_of;  ///< reserved once: the orders point at their keys
  const BandMotion* m_motion;
};

}  // namespace

std::unique_ptr<PixelOrders> PixelOrders::make(DepthSortKind sort, const BandMotion& motion, int width,
                                               int row_begin, int row_end, EventQueue& queue,
                                               uint32_t event_kind, KineticSortStats& stats) {
  KineticSortConfig config;
  config.event_kind = event_kind;
  config.audit = false;  // the band audits at consistent points (not mid flightplan batch)
  config.shared_stats = &stats;
  // A certificate's segment ends at a flightplan update of one of its triangles' meshes, an event
  // of kind kGridFlightplan (0, first at its time), whose handler recomputes every certificate of
  // the pixels holding that mesh's triangles (FrustumBand::handle_flightplans): no renewal events.
  config.renew_at_segment_end = false;
  switch (sort) {
    case DepthSortKind::kList:
      return std::make_unique<PixelOrdersOf<KineticSortedList<PixelDepthKeys>>>(motion, width, row_begin,
                                                                                row_end, queue, config);
    case DepthSortKind::kTournament:
      return std::make_unique<PixelOrdersOf<KineticTournament<PixelDepthKeys>>>(motion, width, row_begin,
                                                                                row_end, queue, config);
    case DepthSortKind::kHeap:
      return std::make_unique<PixelOrdersOf<KineticHeap<PixelDepthKeys>>>(motion, width, row_begin,
                                                                          row_end, queue, config);
  }
  KINRAY_CHECK_MSG(false, "unknown depth sort");
  return nullptr;
}

}  // namespace kinray
