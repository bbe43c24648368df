#pragma once
// Interval arithmetic in round-to-nearest doubles, made outward by widening every result by
// more than its rounding error: enough for the certified signs of primitive CCD's polynomials,
// without switching the FPU's rounding mode. Inputs must stay far from overflow (the caller
// bounds the coordinates); the ends are then finite and never NaN.
#include <algorithm>
#include <cmath>
#include <limits>

namespace kinray::detail {

/// Rounding to nearest is off by at most 2^-53 |x| for normal results and half the smallest
/// subnormal below; moving each end by 2^-51 |x| plus a few subnormals covers that error and
/// the rounding of the widening itself.
inline double round_down_bound(double x) {
  return x - (std::abs(x) * 0x1p-51 + 4 * std::numeric_limits<double>::denorm_min());
}
inline double round_up_bound(double x) {
  return x + (std::abs(x) * 0x1p-51 + 4 * std::numeric_limits<double>::denorm_min());
}

/// A closed interval [lo, hi] that contains the exact value.
struct Interval {
  double lo = 0, hi = 0;

  static Interval point(double x) { return {x, x}; }
  /// Encloses the exact value of which x is a rounding.
  static Interval around(double x) { return {round_down_bound(x), round_up_bound(x)}; }
  [[nodiscard]] bool certainly_positive() const { return lo > 0; }
  [[nodiscard]] bool certainly_negative() const { return hi < 0; }
  [[nodiscard]] bool certainly_nonzero() const { return lo > 0 || hi < 0; }
  /// -1 or 1 when certain, 0 when the interval holds zero.
  [[nodiscard]] int certain_sign() const { return lo > 0 ? 1 : hi < 0 ? -1 : 0; }
};

inline Interval operator+(Interval a, Interval b) {
  return {round_down_bound(a.lo + b.lo), round_up_bound(a.hi + b.hi)};
}
inline Interval operator-(Interval a, Interval b) {
  return {round_down_bound(a.lo - b.hi), round_up_bound(a.hi - b.lo)};
}
inline Interval operator*(Interval a, Interval b) {
  const double p[4] = {a.lo * b.lo, a.lo * b.hi, a.hi * b.lo, a.hi * b.hi};
  return {round_down_bound(std::min({p[0], p[1], p[2], p[3]})),
          round_up_bound(std::max({p[0], p[1], p[2], p[3]}))};
}

struct IntervalVec {
  Interval x, y, z;
};

inline IntervalVec operator+(const IntervalVec& a, const IntervalVec& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline IntervalVec cross(const IntervalVec& a, const IntervalVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Interval dot(const IntervalVec& a, const IntervalVec& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// det(a, b, c) = a . (b x c)
inline Interval det(const IntervalVec& a, const IntervalVec& b, const IntervalVec& c) {
  return dot(a, cross(b, c));
}

}  // namespace kinray::detail
