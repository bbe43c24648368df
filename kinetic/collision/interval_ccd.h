#pragma once
// The floating-point decision of primitive CCD: interval arithmetic over sub-intervals of time,
// refined by bisection. Certifies "no contact" (the coplanarity cubic has no root, or one of
// the 2-D test's polynomials is certainly negative where it may) and, for a simple root at
// which the 2-D test certainly holds, the contact and its time, rounded down to the grid of
// kContactTimeEarliness exactly as the rational decision rounds it (exact_ccd.h). A pair it
// cannot certify (coplanar motion, a root near a segment end, a vertex on an edge, a double
// root) is left to the rational decision.
#include <cstdint>
#include <optional>
#include <vector>

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
/// The sign of the coplanarity cubic det(p1 - p0, p2 - p0, p3 - p0) at local time g, computed
/// in long double with a static bound on its error: -1 or 1 when certain, 0 when the bound
/// cannot decide. Used next to a root, where the double enclosures hold zero (exposed for tests).
[[nodiscard]] int extended_cubic_sign(const PrimitiveMotion& motion, double g);
}  // namespace detail

}  // namespace kinray
