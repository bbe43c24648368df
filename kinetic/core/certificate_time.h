#pragma once
// Failure times of the kinetic grid's coverage certificates. Most of them are quadratics (an edge
// function along one pixel-centre ray), and a boundary that moves across the image makes its
// certificates fail inside almost every segment, so the general root isolation of
// root_finding.h (Bernstein subdivision) would run its slow path for half of them. A quadratic's
// roots are known in closed form: the stable formula gives the crossing to within a few ulps, and
// a short gallop and bisection on Horner's values (exactly as sign_after evaluates them) turns it
// into the time the contract of first_failure asks for. Anything unusual falls back to
// first_failure / schedule_certificate.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "kinetic/core/polynomial.h"

namespace kinray {

/// The floating-point filter in front of the exact search: true when f (stored degree <= 5) is
/// positive on all of [s_now, s_end] by more than any rounding of Horner's rule can take away
/// there, so that no evaluation in the window (all that the exact search and the event handler
/// look at) can see it fail: its two end values clear an error bound, and its minimum on the
/// window is at an end (it opens downwards, or its derivative passes the same test with one
/// sign). False means undecided. Most certificates the grid schedules hold through their
/// segment (every key recomputes all of them), and this spares them the root isolation; degrees
/// 4 and 5 are the pixel orders' depth certificates and their envelopes (decided_despite).
[[nodiscard]] bool holds_through(const Polynomial& f, double s_now, double s_end);

/// The filter for a cubic that has just crossed zero: true only when first_failure(f, s_now,
/// s_end) finds no failure, for f stored and of degree 3 that holds just after s_now >= 0 and at
/// s_end. An orientation certificate rebuilt by its own event starts at a root, and there the
/// Bernstein isolation splits the window's left end down to the noise level (tens of thousands
/// of instructions) before it can say "no failure". Its failure needs a leaf whose first or last
/// coefficient is certainly negative: f(s) < -20 u M(s) at some s of [s_now, s_end (1 + u)]
/// (M(s) = sum |c_k| s^k; the leaves' bound is 40 u M, twice their rounding), or Horner's sign
/// at s_end. This certifies f + 17.1 u M > 0 there: at s_now beyond Horner's rounding, and then
/// rising (its slope passes holds_through), or rising on the first eighth and clearing
/// holds_through on the rest. False means undecided.
[[nodiscard]] bool holds_from_root(const Polynomial& f, double s_now, double s_end);

/// first_failure(f, s_now, s_end) (root_finding.h), with a closed-form path for degree 2.
[[nodiscard]] std::optional<double> first_failure_low_degree(const Polynomial& f, double s_now,
                                                             double s_end);

/// Absolute time of the first failure of the certificate f(t - origin) > 0 after `now`, searched
/// up to `end` (the next flightplan update): `now` when it is already broken just after now, +inf
/// when it holds until end. The returned t satisfies sign_after(f, t - origin) < 0 with the
/// subtraction in double, as the event handler will evaluate it, so the event sees the change.
[[nodiscard]] double certificate_failure_time(const Polynomial& f, double origin, double now, double end);

namespace detail {

/// A quadratic c0 + c1 s + c2 s^2 with exactly the floating-point operations of Polynomial's
/// Horner rule and of sign_after, written out: nearly every coverage certificate is one, and the
/// general loops over a stored degree, the call to sign_after_root and its Taylor shift (taken at
/// every exact 0, which the closed-form root often lands on) were a third of their search.
struct Quadratic {
  double c0, c1, c2;
  /// The same quadratic as a Polynomial, for the general fallbacks.
  [[nodiscard]] Polynomial polynomial() const { return Polynomial{c0, c1, c2}; }
  [[nodiscard]] double operator()(double s) const { return (c2 * s + c1) * s + c0; }
  /// sign_after(f, s): the value's sign; at an exact 0 that of shifted(f, s).c[1], computed as
  /// shifted computes it, (c1 + s c2) + s c2, and then of c2.
  [[nodiscard]] int sign_after(double s) const { return sign_after(s, (*this)(s)); }
  /// sign_after(s) for v = (*this)(s), already evaluated.
  [[nodiscard]] int sign_after(double s, double v) const {
    if (v > 0) return 1;
    if (v < 0) return -1;
    const double d = (c1 + s * c2) + s * c2;
    return d != 0 ? (d > 0) - (d < 0) : (c2 > 0) - (c2 < 0);
  }
  /// holds_through for a stored degree 2 (clear_through<2>, operation for operation), for a
  /// window already checked finite and ordered; value_a = (*this)(a), already evaluated.
  [[nodiscard]] bool holds_through(double a, double b, double big_s, double value_a) const {
    constexpr double kEps = std::numeric_limits<double>::epsilon();
    const double margin =
        32 * kEps * ((std::fabs(c2) * big_s + std::fabs(c1)) * big_s + std::fabs(c0));
    if (!(std::isfinite(margin) && value_a > margin && (*this)(b) > margin)) return false;
    if (c2 < 0) return true;
    // The slope c1 + 2 c2 s clears its own margin at both ends with one sign.
    const double slope_margin = 16 * kEps * (std::fabs(2 * c2) * big_s + std::fabs(c1));
    if (!std::isfinite(slope_margin)) return false;
    const double at_a = 2 * c2 * a + c1, at_b = 2 * c2 * b + c1;
    return (at_a > slope_margin && at_b > slope_margin) ||
           (-at_a > slope_margin && -at_b > slope_margin);
  }
};

/// certificate_failure_time of a stored quadratic that the filter did not decide: the closed-form
/// search of first_failure_low_degree, step for step on Quadratic's operations; at_now =
/// q(now - origin), already evaluated.
[[nodiscard]] double undecided_quadratic_failure_time(const Quadratic& q, double at_now,
                                                      double origin, double now, double end);

}  // namespace detail

/// certificate_failure_time of sign (c0 + c1 s + c2 s^2), a quadratic stored with degree 2
/// (sign +1 or -1), without building the polynomial: the same time. `value_now` is its Horner
/// value (c2 s + c1) s + c0 at s = now - origin, which the caller has (a boundary event's
/// EdgeOnRay) and which the filter and the search would otherwise evaluate again. Inline: the
/// filter decides most boundary certificates, two per boundary event.
[[nodiscard]] inline double quadratic_failure_time(int sign, double c0, double c1, double c2,
                                                   double value_now, double origin, double now,
                                                   double end) {
  // -f negates each coefficient exactly, and so Horner's value: this is the quadratic -f holds.
  const detail::Quadratic q =
      sign > 0 ? detail::Quadratic{c0, c1, c2} : detail::Quadratic{-c0, -c1, -c2};
  const double at_now = sign > 0 ? value_now : -value_now;
  const double s_now = now - origin, s_end = end - origin;
  if (std::isfinite(s_now) && std::isfinite(s_end) && s_end >= s_now &&
      q.holds_through(s_now, s_end, std::max(std::fabs(s_now), std::fabs(s_end)), at_now))
    return std::numeric_limits<double>::infinity();
  return detail::undecided_quadratic_failure_time(q, at_now, origin, now, end);
}
/// The same, Horner's value at now evaluated here.
[[nodiscard]] inline double quadratic_failure_time(int sign, double c0, double c1, double c2,
                                                   double origin, double now, double end) {
  const double s_now = now - origin;
  return quadratic_failure_time(sign, c0, c1, c2, (c2 * s_now + c1) * s_now + c0, origin, now, end);
}

/// certificate_failure_time of sign f (sign +1 or -1) without building -f: the same time, as
/// the negation of each coefficient is exact.
[[nodiscard]] double certificate_failure_time(int sign, const Polynomial& f, double origin,
                                              double now, double end);

}  // namespace kinray
