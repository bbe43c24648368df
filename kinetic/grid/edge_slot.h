#pragma once
// Locating an edge's boundary point among the columns of a row: the slot SlotCircle::locate's
// bisection finds over the edge's signs (edge_sign), usually from four edge functions instead of
// the eleven of the bisection.
#include <algorithm>
#include <cmath>
#include <optional>

#include "kinetic/grid/coverage_rule.h"
#include "kinetic/grid/row_record.h"

namespace kinray {

/// A slot on the circle of columns and the edge's signs at its two watched columns.
struct EdgeSlot {
  int slot = 0;
  int sign_lo = 1, sign_hi = 1;
};

namespace detail {

/// The slot hi (1 <= hi < count) when the computed signs along the row are provably one step,
/// `first_sign` up to column hi - 1 and the other sign from hi on; std::nullopt when that cannot
/// be shown cheaply. `first` and `last` are the edge function at columns 0 and count - 1, of
/// different signs.
///
/// Exact E(x) = sum_k (a_k x + b_k y + z_k) s^k is linear in x, alpha x + beta, and the columns'
/// x increase, so its signs are one step. EdgeOnRay's value v at column x is E(x) up to
/// B(x) = 7.001 u (A |x| + C), A = sum |a_k| |s|^k, C = sum (|b_k| |y| + |z_k|) |s|^k (three
/// roundings per coefficient, four in Horner's rule); the bound below is more than four times
/// that. Where |v| > 2 bound, E has v's sign and |E| - B > 0. If that holds at two adjacent
/// columns lo, hi of opposite signs, E's root lies between them, and if |alpha| >= 7.001 u A
/// (its Horner value clears that and its own rounding, 4.001 u A), |E| grows away from the root
/// at least as fast as B, so |E| > B at every column: every computed sign is the exact one, one
/// step at hi, which is where the bisection ends.
template <class Ray>
std::optional<EdgeSlot> certified_step(const EdgeNormal& n, int count, double y, double s,
                                       int first_sign, const EdgeOnRay& first,
                                       const EdgeOnRay& last, Ray&& ray) {
  const double as = std::fabs(s);
  auto magnitude = [&](double c2, double c1, double c0) {
    return (std::fabs(c2) * as + std::fabs(c1)) * as + std::fabs(c0);
  };
  const double slope_magnitude = magnitude(n.c2.x(), n.c1.x(), n.c0.x());
  const double rest_magnitude = magnitude(n.c2.y(), n.c1.y(), n.c0.y()) * std::fabs(y) +
                                magnitude(n.c2.z(), n.c1.z(), n.c0.z());
  constexpr double kRelative = 0x1p-48;  // 32 u
  const double slope = (n.c2.x() * s + n.c1.x()) * s + n.c0.x();
  if (!(std::fabs(slope) > kRelative * slope_magnitude)) return std::nullopt;
  // The last term covers underflow in the products (absolute errors of 2^-1074 each).
  const double floor = 0x1p-1000 * (1 + as) * (1 + as);
  auto certain = [&](const EdgeOnRay& r) {
    return std::fabs(r.v) >
           2 * (kRelative * (slope_magnitude * std::fabs(r.x) + rest_magnitude) + floor);
  };
  // The guess: where the line through the two end values vanishes.
  const double t = first.v / (first.v - last.v);
  int hi = t >= 0 && t <= 1 ? int(t * (count - 1)) + 1 : count / 2;
  hi = std::clamp(hi, 1, count - 1);
  for (int tries = 0; tries < 4; ++tries) {
    const EdgeOnRay lo_ray = hi - 1 == 0 ? first : ray(hi - 1);
    const EdgeOnRay hi_ray = hi == count - 1 ? last : ray(hi);
    const int sign_lo = lo_ray.sign(n, y, s), sign_hi = hi_ray.sign(n, y, s);
    if (sign_lo != first_sign) {  // then hi - 1 > 0: column 0 has first_sign
      --hi;
    } else if (sign_hi == first_sign) {  // then hi < count - 1: column count - 1 has the other
      ++hi;
    } else {
      if (certain(lo_ray) && certain(hi_ray)) return EdgeSlot{hi, sign_lo, sign_hi};
      return std::nullopt;
    }
  }
  return std::nullopt;
}

}  // namespace detail

/// The slot by SlotCircle::locate's bisection over sign_at (a column's computed edge sign), and
/// the signs at its watched columns: what locate_edge_slot falls back to, and the reference the
/// certified step must agree with.
template <class SignAt>
[[nodiscard]] EdgeSlot bisected_edge_slot(const SlotCircle& columns, SignAt&& sign_at) {
  EdgeSlot out;
  out.slot = columns.locate(sign_at);
  const auto [lo, hi] = columns.watched(out.slot);
  out.sign_lo = sign_at(lo);
  out.sign_hi = lo == hi ? out.sign_lo : sign_at(hi);
  return out;
}

/// The slot of the edge n's boundary point among the columns of row y just after s, and its
/// signs at the two watched columns: exactly those of columns.locate over
/// edge_sign(n, column_x(c), y, s) and edge_sign at columns.watched(slot). column_x(c) must not
/// decrease with c. Where
/// the step is not proven (a nearly constant edge function, a column within rounding of the
/// point) the bisection decides.
template <class ColumnX>
[[nodiscard]] EdgeSlot locate_edge_slot(const EdgeNormal& n, const SlotCircle& columns,
                                        ColumnX&& column_x, double y, double s) {
  auto ray = [&](int c) { return EdgeOnRay(n, column_x(c), y, s); };
  const EdgeOnRay first = ray(0);
  const int first_sign = first.sign(n, y, s);
  if (columns.count == 1) return EdgeSlot{0, first_sign, first_sign};
  const EdgeOnRay last = ray(columns.count - 1);
  const int last_sign = last.sign(n, y, s);
  if (last_sign == first_sign) return EdgeSlot{0, first_sign, last_sign};
  if (const std::optional<EdgeSlot> step =
          detail::certified_step(n, columns.count, y, s, first_sign, first, last, ray))
    return *step;
  return bisected_edge_slot(columns, [&](int c) { return ray(c).sign(n, y, s); });
}

}  // namespace kinray
