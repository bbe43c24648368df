#pragma once
// Small helpers of the frustum band (kinetic/frustum_band_*.cpp) for the rows a triangle meets and
// the runs of columns or rows between cuts.
#include <array>
#include <cstddef>

#include "kinetic/motion/triangle_motion.h"

namespace kinray::detail {

/// The edges whose end points lie on different sides (`sides`, one per vertex): none or two of
/// them; the first two are written to `out`.
inline int crossing_edges(const std::array<int, 3>& sides, int out[2]) {
  int n = 0;
  for (int e = 0; e < 3; ++e)
    if (sides[size_t(kEdgeStart[e])] != sides[size_t(kEdgeEnd[e])]) {
      if (n < 2) out[n] = e;
      ++n;
    }
  return n;
}

/// A vertex's row pattern (sign_lo on the rows before `slot`, sign_hi from it on) as a function
/// of the rows [0, count): its first and last sign, and the row where it steps (0 if it does
/// not). Each pattern steps at most once, at its slot, so two patterns are the same function of
/// the rows iff their keys are equal: a triangle meets a row of the band iff its three vertices'
/// keys are not all equal.
struct RowStep {
  int first = 1, last = 1, step = 0;
  bool operator==(const RowStep&) const = default;
};
inline RowStep row_step(int slot, int sign_lo, int sign_hi, int count) {
  const int first = 0 < slot ? sign_lo : sign_hi, last = count - 1 < slot ? sign_lo : sign_hi;
  return {first, last, first != last ? slot : 0};
}

/// Sorts the 4 or 5 cuts of a row or a band in place: an insertion sort, inline (std::sort's call
/// and introsort set-up cost more than the sort itself here; the result is the same).
template <size_t N>
void sort_cuts(int (&cuts)[N]) {
  for (size_t i = 1; i < N; ++i) {
    const int v = cuts[i];
    size_t j = i;
    for (; j > 0 && cuts[j - 1] > v; --j) cuts[j] = cuts[j - 1];
    cuts[j] = v;
  }
}

}  // namespace kinray::detail
