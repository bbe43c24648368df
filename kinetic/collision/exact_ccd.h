#pragma once
// Exact continuous collision detection of one primitive pair with rational coordinates: the
// answer floating point cannot give when the pair is (nearly) coplanar, parallel, touching at a
// segment end or sliding in contact.
#include <gmpxx.h>

#include <array>
#include <vector>

#include "kinetic/collision/contact_pair.h"
#include "kinetic/core/rational_polynomial.h"

namespace kinray {

using RationalPoint = std::array<mpq_class, 3>;

/// PrimitiveMotion with rational coordinates (doubles convert to them exactly).
struct RationalMotion {
  std::array<RationalPoint, 4> start{};
  std::array<RationalPoint, 4> end{};
};

/// Local times in [0, 1] reported per contact are lower bounds: a reported t satisfies
/// t* - kContactTimeEarliness < t <= t* for the exact time of contact t*. Precisely, t is t*
/// rounded down to the grid of multiples of kContactTimeEarliness, a function of t* alone, so
/// that the floating-point decision (interval_ccd.h) and the rational one report the same time
/// for the same contact, and one primitive pair met with its points in another order too.
inline constexpr double kContactTimeEarliness = 0x1p-48;

/// Exact rational conversion of a double motion (every finite double is a rational).
[[nodiscard]] RationalMotion to_rational(const PrimitiveMotion& motion);

/// det(p1 - p0, p2 - p0, p3 - p0) as a polynomial in local time: zero exactly when the four
/// points are coplanar.
[[nodiscard]] RationalPolynomial coplanarity_polynomial(const RationalMotion& motion);

/// Every time of contact in [0, 1], sorted, decided exactly: the roots of the coplanarity cubic
/// at which the vertex lies in the closed triangle (or the closed edges meet). When the cubic
/// vanishes identically (coplanar motion) the contact set may be a whole interval: then every
/// interval of contact is reported by its first and last times alone (the same for every order
/// of the points), found among 0, 1 and the roots of the polynomials whose signs decide the 2-D
/// test.
/// Each time is rounded down to the grid of kContactTimeEarliness. With a window: exactly those
/// of these times whose exact time lies in it.
[[nodiscard]] std::vector<double> exact_contact_times(ContactType type,
                                                      const RationalMotion& motion,
                                                      LocalWindow window = {});

}  // namespace kinray
