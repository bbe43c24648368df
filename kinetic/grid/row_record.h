#pragma once
// Per (triangle, row) bookkeeping of the kinetic grid (docs/design.md,
// "Coverage"). The centre rays of row j span the plane Pi_j through the eye; a triangle meeting
// Pi_j does so in a segment whose two end points (the boundaries) lie on two of its edges. Each
// boundary's column position lives on the projective line of the row and is tracked by a slot on
// a circle of columns, once per (edge, row) for the two triangles of the edge; the record keeps
// the interval of columns the triangle covers.
//
// The same slot circle tracks a vertex among the row planes of a band.
#include <algorithm>
#include <array>
#include <cstdint>
#include <utility>

#include "kinetic/core/event_queue.h"

namespace kinray {

/// `count` positions 0..count-1 (the columns of a row, or the rows of a band) on a projective
/// circle joined through infinity. Slot k in 1..count-1 lies between positions k-1 and k; slot 0,
/// "off", is left of position 0 or right of position count-1 (the two are one arc through
/// infinity, so a point that wraps around is still caught). A point in a slot watches the two
/// positions that bracket it (off: 0 and count-1) through the signs of a function that is linear
/// along the positions (an edge function along a row, a row side along the rows): in slot k the
/// two signs differ, in the off slot they agree.
struct SlotCircle {
  int count = 1;

  /// The positions watched in `slot`.
  [[nodiscard]] std::pair<int, int> watched(int slot) const {
    return slot == 0 ? std::pair<int, int>{0, count - 1} : std::pair<int, int>{slot - 1, slot};
  }
  /// The slot on the other side of `position` from `slot` (which must be next to it).
  [[nodiscard]] int across(int slot, int position) const {
    const int below = position, above = position + 1 == count ? 0 : position + 1;
    return slot == below ? above : below;
  }
  [[nodiscard]] static bool consistent(int slot, int sign_lo, int sign_hi) {
    return slot == 0 ? sign_lo == sign_hi : sign_lo != sign_hi;
  }
  /// The slot of a monotone sign pattern sign_at(0..count-1) (values +-1), by bisection.
  template <class SignAt>
  [[nodiscard]] int locate(SignAt&& sign_at) const {
    const int first = sign_at(0);
    if (count == 1 || sign_at(count - 1) == first) return 0;
    int lo = 0, hi = count - 1;  // sign_at(lo) == first != sign_at(hi)
    while (hi - lo > 1) {
      const int mid = lo + (hi - lo) / 2;
      (sign_at(mid) == first ? lo : hi) = mid;
    }
    return hi;
  }
};

/// The slot of a boundary whose point lies behind the eye plane: its crossings of column centres
/// change nothing visible (the sign rule), so it watches only its depth; it can come back in
/// front only through the eye plane, where its column position is at infinity: the off slot.
inline constexpr int32_t kBehindEye = -1;

/// A point tracked on a slot circle: its slot, the signs at the two watched positions, and the
/// queue entry of the earlier failure of its certificates "sign keeps its value" (a boundary in
/// the off slot also watches that its point stays in front of the eye plane).
struct SlotTracker {
  int32_t slot = 0;  ///< boundaries: kBehindEye when the point is behind the eye
  int8_t sign_lo = 1, sign_hi = 1;
  EventHandle event = kNoEvent;
};

inline constexpr uint32_t kNoRecord = ~0u;
inline constexpr uint32_t kNoBoundary = ~0u;

/// The point where one mesh edge meets one row plane, tracked among the row's columns. The signs
/// are those of the edge function in the edge's own direction (GridScene::edge_vertices). Both
/// triangles of the edge bound their row segments there, so the two share it: one certificate
/// and one event per crossing of a column centre, which moves the pixel from one triangle to the
/// other. A triangle on the other side that keeps no record (it faces away) leaves it to one.
struct EdgeBoundary {
  uint32_t edge = 0;                ///< global edge id
  int32_t row = 0;
  uint32_t next = kNoBoundary;      ///< the next boundary of the same edge in the band (a list)
  std::array<uint32_t, 2> records = {kNoRecord, kNoRecord};  ///< the records bounded here
  SlotTracker tracker;

  [[nodiscard]] bool unused() const { return records[0] == kNoRecord && records[1] == kNoRecord; }
};

/// One (triangle, row) whose triangle meets the row plane: its segment there runs between the
/// points of two of its edges, each an EdgeBoundary.
struct RowRecord {
  uint32_t triangle = 0;     ///< global triangle id
  int32_t row = 0;
  uint32_t next = kNoRecord; ///< the next record of the same triangle in the band (a list)
  int32_t lo = 0, hi = -1;   ///< covered columns [lo, hi]; empty when lo > hi
  std::array<uint32_t, 2> boundary = {kNoBoundary, kNoBoundary};  ///< EdgeBoundary ids
  std::array<uint8_t, 2> edge = {0, 0};  ///< the boundaries' edges (0: v0v1, 1: v1v2, 2: v2v0)

  [[nodiscard]] bool covers(int column) const { return column >= lo && column <= hi; }
  [[nodiscard]] bool empty() const { return lo > hi; }
  [[nodiscard]] int covered_count() const { return empty() ? 0 : hi - lo + 1; }
};

}  // namespace kinray
