#pragma once
// A polynomial on an interval of time in Bernstein form, held as double coefficients and one
// bound, `slack`, on how far the exact polynomial's Bernstein coefficients may be from them.
// The Bernstein basis is non-negative and sums to one, so on the interval the exact polynomial
// lies within [min c - slack, max c + slack], and at the interval's ends it is c[0] and c[N]
// within slack. Halving the interval (de Casteljau at 1/2) averages coefficients: the exact
// halves' coefficients stay within the parent's slack of the averages, and the averages are
// off by their rounding, at most N roundings of u max |c|. So the primitive test's polynomials
// are enclosed once per pair, in interval arithmetic, and every piece of the bisection after
// that costs a few additions instead of an interval evaluation of each polynomial.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "kinetic/core/interval_arithmetic.h"

namespace kinray::detail {

/// A double computed from inputs known to within a few roundings of their magnitudes, with the
/// magnitude of the terms it was computed from: along any path of k operations from the
/// inputs, products add the factors' relative errors and sums keep the larger, so the value is
/// off by at most (input error + k u) times `magnitude` (forward error analysis, as in
/// Shewchuk's bounds for orient3d). One multiple of the magnitude at the end bounds the error:
/// half the cost of interval arithmetic, and no min or max.
struct Tracked {
  double value = 0, magnitude = 0;
};
inline Tracked operator+(Tracked a, Tracked b) {
  return {a.value + b.value, a.magnitude + b.magnitude};
}
inline Tracked operator-(Tracked a, Tracked b) {
  return {a.value - b.value, a.magnitude + b.magnitude};
}
inline Tracked operator*(Tracked a, Tracked b) {
  return {a.value * b.value, a.magnitude * b.magnitude};
}
struct TrackedVec {
  Tracked x, y, z;
};
inline TrackedVec operator+(const TrackedVec& a, const TrackedVec& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline TrackedVec operator*(double w, const TrackedVec& a) {
  const Tracked s{w, std::fabs(w)};
  return {s * a.x, s * a.y, s * a.z};
}
inline TrackedVec cross(const TrackedVec& a, const TrackedVec& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline Tracked dot(const TrackedVec& a, const TrackedVec& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}

template <int N>
struct BernsteinBound {
  std::array<double, N + 1> c{};
  double slack = 0;

  /// From interval enclosures of the exact coefficients: their midpoints, and the largest
  /// distance to an end, rounded up.
  static BernsteinBound enclosing(const std::array<Interval, N + 1>& b) {
    BernsteinBound out;
    for (int k = 0; k <= N; ++k) {
      out.c[k] = 0.5 * (b[k].lo + b[k].hi);
      out.slack =
          std::max(out.slack, round_up_bound(std::max(b[k].hi - out.c[k], out.c[k] - b[k].lo)));
    }
    return out;
  }

  /// From tracked values of the exact coefficients, each off by at most `relative` times its
  /// magnitude (and a few subnormals, where products underflow).
  static BernsteinBound tracking(const std::array<Tracked, N + 1>& b, double relative) {
    BernsteinBound out;
    for (int k = 0; k <= N; ++k) {
      out.c[k] = b[k].value;
      out.slack = std::max(out.slack, relative * b[k].magnitude);
    }
    out.slack = round_up_bound(out.slack + 256 * std::numeric_limits<double>::denorm_min());
    return out;
  }

  [[nodiscard]] bool certainly_positive() const {
    return *std::min_element(c.begin(), c.end()) > slack;
  }
  [[nodiscard]] bool certainly_negative() const {
    return *std::max_element(c.begin(), c.end()) < -slack;
  }
  [[nodiscard]] bool certainly_nonzero() const {
    return certainly_positive() || certainly_negative();
  }
  /// -1 or 1 when the sign at the interval's start (end) is certain, else 0.
  [[nodiscard]] int start_sign() const { return c[0] > slack ? 1 : c[0] < -slack ? -1 : 0; }
  [[nodiscard]] int end_sign() const { return c[N] > slack ? 1 : c[N] < -slack ? -1 : 0; }

  /// The derivative's Bernstein coefficients are N (c[k+1] - c[k]) / (interval length): the
  /// differences, off by twice the slack plus their rounding, all certainly of one sign.
  [[nodiscard]] bool certainly_monotone() const {
    int positive = 0, negative = 0;
    for (int k = 0; k < N; ++k) {
      const double d = c[k + 1] - c[k];
      const double bound =
          round_up_bound(2 * slack + std::numeric_limits<double>::epsilon() * std::fabs(d) +
                         4 * std::numeric_limits<double>::denorm_min());
      positive += d > bound;
      negative += d < -bound;
    }
    return positive == N || negative == N;
  }

  /// The two halves of the interval, by de Casteljau's midpoint steps.
  [[nodiscard]] std::pair<BernsteinBound, BernsteinBound> halves() const {
    BernsteinBound left, right;
    std::array<double, N + 1> row = c;
    double largest = 0;
    for (double x : c) largest = std::max(largest, std::fabs(x));
    left.c[0] = row[0];
    right.c[N] = row[N];
    for (int level = 1; level <= N; ++level) {
      for (int k = 0; k + level <= N; ++k) row[k] = 0.5 * (row[k] + row[k + 1]);
      left.c[level] = row[0];
      right.c[N - level] = row[N - level];
    }
    // each level rounds each average by at most u |average| <= u (1 + u)^N largest, plus half
    // a subnormal; averaging does not grow earlier errors
    left.slack = right.slack =
        round_up_bound(slack + N * (std::numeric_limits<double>::epsilon() * largest +
                                    4 * std::numeric_limits<double>::denorm_min()));
    return {left, right};
  }
};

}  // namespace kinray::detail
