#pragma once
// Failure times of the kinetic grid's coverage certificates. Most of them are quadratics (an edge
// function along one pixel-centre ray), and a boundary that moves across the image makes its
// certificates fail inside almost every segment, so the general root isolation of
// root_finding.h (Bernstein subdivision) would run its slow path for half of them. A quadratic's
// roots are known in closed form: the stable formula gives the crossing to within a few ulps, and
// a short gallop and bisection on Horner's values (exactly as sign_after evaluates them) turns it
// into the time the contract of first_failure asks for. Anything unusual falls back to
// first_failure / schedule_certificate.
#include <optional>

#include "kinetic/polynomial.h"

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

/// certificate_failure_time of sign (c0 + c1 s + c2 s^2), a quadratic stored with degree 2
/// (sign +1 or -1), without building the polynomial: the same time.
[[nodiscard]] double quadratic_failure_time(int sign, double c0, double c1, double c2,
                                            double origin, double now, double end);

/// certificate_failure_time of sign f (sign +1 or -1) without building -f: the same time, as
/// the negation of each coefficient is exact.
[[nodiscard]] double certificate_failure_time(int sign, const Polynomial& f, double origin,
                                              double now, double end);

}  // namespace kinray
