#pragma once
// Interval arithmetic in round-to-nearest doubles, made outward by widening every result by
// more than its rounding error: enough for the certified signs of primitive CCD's polynomials,
// without switching the FPU's rounding mode. Inputs must stay far from overflow (the caller
// bounds the coordinates); the ends are then finite and never NaN.
#include <algorithm>
#include <cmath>
#include <limits>

namespace kinray::detail {

/// Rounding to nearest is off by at most epsilon/2 |x| for normal results and half the smallest
/// subnormal below; moving each end by 2 epsilon |x| plus a few subnormals covers that error and
/// the rounding of the widening itself.
template <class S>
S round_down_bound(S x) {
  return x - (std::abs(x) * (2 * std::numeric_limits<S>::epsilon()) +
              4 * std::numeric_limits<S>::denorm_min());
}
template <class S>
S round_up_bound(S x) {
  return x + (std::abs(x) * (2 * std::numeric_limits<S>::epsilon()) +
              4 * std::numeric_limits<S>::denorm_min());
}

/// A closed interval [lo, hi] that contains the exact value, with ends of type S (double, or
/// long double where a few more bits decide what double cannot).
template <class S>
struct BasicInterval {
  S lo = 0, hi = 0;

  static BasicInterval point(S x) { return {x, x}; }
  /// Encloses the exact value of which x is a rounding.
  static BasicInterval around(S x) { return {round_down_bound(x), round_up_bound(x)}; }
  [[nodiscard]] bool certainly_positive() const { return lo > 0; }
  [[nodiscard]] bool certainly_negative() const { return hi < 0; }
  [[nodiscard]] bool certainly_nonzero() const { return lo > 0 || hi < 0; }
  /// -1 or 1 when certain, 0 when the interval holds zero.
  [[nodiscard]] int certain_sign() const { return lo > 0 ? 1 : hi < 0 ? -1 : 0; }
};

template <class S>
BasicInterval<S> operator+(BasicInterval<S> a, BasicInterval<S> b) {
  return {round_down_bound(a.lo + b.lo), round_up_bound(a.hi + b.hi)};
}
template <class S>
BasicInterval<S> operator-(BasicInterval<S> a, BasicInterval<S> b) {
  return {round_down_bound(a.lo - b.hi), round_up_bound(a.hi - b.lo)};
}
/// The four end products, their least and greatest taken pairwise: branch-free min and max
/// instructions (an initializer-list std::min made this a loop and a call, a third of the
/// primitive CCD's time).
template <class S>
inline BasicInterval<S> operator*(BasicInterval<S> a, BasicInterval<S> b) {
  const S p0 = a.lo * b.lo, p1 = a.lo * b.hi, p2 = a.hi * b.lo, p3 = a.hi * b.hi;
  const S lo = std::min(std::min(p0, p1), std::min(p2, p3));
  const S hi = std::max(std::max(p0, p1), std::max(p2, p3));
  return {round_down_bound(lo), round_up_bound(hi)};
}

template <class S>
struct BasicIntervalVec {
  BasicInterval<S> x, y, z;
};

template <class S>
BasicIntervalVec<S> cross(const BasicIntervalVec<S>& a, const BasicIntervalVec<S>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class S>
BasicInterval<S> dot(const BasicIntervalVec<S>& a, const BasicIntervalVec<S>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
/// det(a, b, c) = a . (b x c)
template <class S>
BasicInterval<S> det(const BasicIntervalVec<S>& a, const BasicIntervalVec<S>& b,
                     const BasicIntervalVec<S>& c) {
  return dot(a, cross(b, c));
}

using Interval = BasicInterval<double>;
using IntervalVec = BasicIntervalVec<double>;

}  // namespace kinray::detail
