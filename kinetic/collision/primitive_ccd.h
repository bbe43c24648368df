#pragma once
// The primitive test of continuous collision detection, for doubles: a floating-point filter
// that rejects with certified error bounds, and the exact rational decision (exact_ccd.h) for
// every pair the filter cannot reject. Conservative: no contact is ever missed.
#include <cstdint>
#include <vector>

#include "kinetic/collision/contact_pair.h"

namespace kinray {

/// How the primitive tests were decided (for --stats).
struct PrimitiveCcdCounters {
  std::uint64_t tests = 0;             ///< primitive pairs tested
  std::uint64_t box_rejections = 0;    ///< separated swept boxes
  std::uint64_t cubic_rejections = 0;  ///< coplanarity cubic of one certified sign on [0, 1]
  std::uint64_t exact_decisions = 0;   ///< decided in rational arithmetic
  std::uint64_t contacts = 0;          ///< pairs with at least one time of contact

  PrimitiveCcdCounters& operator+=(const PrimitiveCcdCounters& o);
};

/// Every time of contact of the pair in local time [0, 1], sorted; each time t satisfies
/// t* - kContactTimeEarliness <= t <= t* (exact_ccd.h). Coordinates must be finite.
[[nodiscard]] std::vector<double> contact_times(ContactType type, const PrimitiveMotion& motion,
                                                PrimitiveCcdCounters* counters = nullptr);

/// Where the pair touches at local time t (a point of the vertex, or the midpoint of the two
/// edges' closest points), in double precision.
[[nodiscard]] Eigen::Vector3d contact_point(ContactType type, const PrimitiveMotion& motion,
                                            double t);

}  // namespace kinray
