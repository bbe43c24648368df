#pragma once
// The primitive test of continuous collision detection, for doubles: floating-point filters
// that reject with certified error bounds, the interval decision that certifies contacts and
// their times (interval_ccd.h), and the exact rational decision (exact_ccd.h) for every pair
// floating point cannot certify. Conservative: no contact is ever missed.
#include <cstdint>
#include <vector>

#include "kinetic/collision/contact_pair.h"

namespace kinray {

/// How the primitive tests were decided (for --stats).
struct PrimitiveCcdCounters {
  std::uint64_t tests = 0;             ///< primitive pairs tested
  std::uint64_t box_rejections = 0;    ///< separated swept boxes
  std::uint64_t cubic_rejections = 0;  ///< coplanarity cubic of one certified sign on [0, 1]
  std::uint64_t interval_rejections = 0;  ///< no contact, certified by interval arithmetic
  std::uint64_t interval_contacts = 0;    ///< contacts and times certified by intervals
  std::uint64_t exact_signs = 0;       ///< grid points of interval contacts signed in rationals
  std::uint64_t exact_decisions = 0;   ///< decided in rational arithmetic
  std::uint64_t contacts = 0;          ///< pairs with at least one time of contact

  PrimitiveCcdCounters& operator+=(const PrimitiveCcdCounters& o);
};

/// Every time of contact of the pair in local time [0, 1] (in `window`), sorted; each time t
/// satisfies t* - kContactTimeEarliness <= t <= t* (exact_ccd.h). Coordinates must be finite.
[[nodiscard]] std::vector<double> contact_times(ContactType type, const PrimitiveMotion& motion,
                                                PrimitiveCcdCounters* counters = nullptr,
                                                LocalWindow window = {});

/// Where the pair touches at local time t (a point of the vertex, or the midpoint of the two
/// edges' closest points), in double precision.
[[nodiscard]] Eigen::Vector3d contact_point(ContactType type, const PrimitiveMotion& motion,
                                            double t);

}  // namespace kinray
