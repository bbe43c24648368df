#pragma once
// The floating-point decision of primitive CCD: interval arithmetic over sub-intervals of time,
// refined by bisection. Certifies "no contact" (the coplanarity cubic has no root, or one of
// the 2-D test's polynomials is certainly negative where it may) and, for a simple root at
// which the 2-D test certainly holds, the contact and its time, rounded down to the grid of
// kContactTimeEarliness exactly as the rational decision rounds it (exact_ccd.h). A vertex on
// an edge, where a condition vanishes at the contact, is certified when the three points lie on
// an axis plane that the fourth never meets (axis_plane.h), and edges sliding in an axis plane
// (coplanar motion there) by the times their contact intervals begin and end; a pair it cannot
// certify (other coplanar motion, a root near a segment end, a vertex on an edge elsewhere, a
// double root) is left to the rational decision.
#include <cstdint>
#include <optional>
#include <vector>

#include "kinetic/collision/bernstein_bound.h"
#include "kinetic/collision/contact_pair.h"

namespace kinray {

/// What the interval decision did (summed into PrimitiveCcdCounters).
struct IntervalCcdCounters {
  std::uint64_t rejections = 0;   ///< pairs certified free of contact
  std::uint64_t contacts = 0;     ///< pairs whose every contact time was certified
  std::uint64_t exact_signs = 0;  ///< grid points too close to a root, signed in rationals
};

/// Every time of contact in local time [0, 1] (in `window`), sorted, each floor(t* / e) e for
/// the exact contact time t* and e = kContactTimeEarliness; or nothing when floating point
/// cannot certify the answer. Coordinates must be finite.
[[nodiscard]] std::optional<std::vector<double>> interval_contact_times(
    ContactType type, const PrimitiveMotion& motion, IntervalCcdCounters& counters,
    LocalWindow window = {});

namespace detail {
/// The coplanarity cubic det(p1 - p0, p2 - p0, p3 - p0) on [lo, hi] in Bernstein form (times
/// 3): it is trilinear in the three differences X, Y, Z, so b_k = sum_{i+j+l=k} det(X_i, Y_j,
/// Z_l) / C(3, k), X_0 and X_1 the values at lo and hi. Each coefficient is kept with the
/// magnitude of its terms, and is off by at most `relative` times it. Computed once per
/// primitive pair on [0, 1]: the filter in front of the interval decision, and (for a whole
/// segment) that decision's first piece and the guide of its root search.
struct CoplanarityCubic {
  std::array<Tracked, 4> b{};
  double relative = 0;

  CoplanarityCubic(const PrimitiveMotion& motion, double lo, double hi);
  /// Every coefficient of one sign beyond its own error: no root on [lo, hi].
  [[nodiscard]] bool certainly_nonzero() const;
  /// With one slack for all four coefficients, for the bisection.
  [[nodiscard]] BernsteinBound<3> bound() const { return BernsteinBound<3>::tracking(b, relative); }
};
}  // namespace detail

/// The same with the coplanarity cubic on the window already computed (CoplanarityCubic).
[[nodiscard]] std::optional<std::vector<double>> interval_contact_times(
    ContactType type, const PrimitiveMotion& motion, IntervalCcdCounters& counters,
    LocalWindow window, const detail::BernsteinBound<3>& cubic);

namespace detail {
/// The sign of the coplanarity cubic det(p1 - p0, p2 - p0, p3 - p0) at local time g, computed
/// in long double with a static bound on its error: -1 or 1 when certain, 0 when the bound
/// cannot decide. Used next to a root, where the double enclosures hold zero (exposed for tests).
[[nodiscard]] int extended_cubic_sign(const PrimitiveMotion& motion, double g);
}  // namespace detail

}  // namespace kinray
