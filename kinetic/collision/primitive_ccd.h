#pragma once
// The primitive test of continuous collision detection, for doubles: floating-point filters
// that reject with certified error bounds, the interval decision that certifies contacts and
// their times (interval_ccd.h), and the exact rational decision (exact_ccd.h) for every pair
// floating point cannot certify. Conservative: no contact is ever missed.
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "kinetic/collision/contact_pair.h"
#include "kinetic/core/counters.h"

namespace kinray {

// X(member, "stats key") of PrimitiveCcdCounters (kinetic/core/counters.h).
#define KINRAY_PRIMITIVE_CCD_COUNTERS(X)                                                       \
  X(tests, "primitive_tests")                 /* primitive pairs tested */                     \
  X(box_rejections, "box_rejections")         /* separated swept boxes */                      \
  X(cubic_rejections, "cubic_rejections")     /* coplanarity cubic of one sign on [0, 1] */    \
  X(interval_rejections, "interval_rejections") /* no contact, certified by intervals */       \
  X(interval_contacts, "interval_contacts")   /* contacts and times certified by intervals */  \
  X(exact_signs, "exact_signs")     /* grid points of interval contacts signed in rationals */ \
  X(exact_decisions, "exact_decisions")       /* decided in rational arithmetic */             \
  X(contacts, "primitive_pairs_in_contact")   /* pairs with at least one time of contact */

/// How the primitive tests were decided (for --stats).
struct PrimitiveCcdCounters {
  KINRAY_COUNTERS(PrimitiveCcdCounters, KINRAY_PRIMITIVE_CCD_COUNTERS)
};

/// Every time of contact of the pair in local time [0, 1] (in `window`), sorted; each time t
/// satisfies t* - kContactTimeEarliness <= t <= t* (exact_ccd.h). Coordinates must be finite.
[[nodiscard]] std::vector<double> contact_times(ContactType type, const PrimitiveMotion& motion,
                                                PrimitiveCcdCounters* counters = nullptr,
                                                LocalWindow window = {});

/// One primitive pair of a batch (first_contact_times).
struct PrimitiveQuery {
  ContactType type = ContactType::vertex_face;
  PrimitiveMotion motion;
};

/// Options of first_contact_times.
struct PrimitiveCcdBatchConfig {
  int threads = 1;  ///< 0: all cores
};

/// Each pair's first time of contact in [0, 1] (contact_times' first), std::nullopt where it
/// has none, in input order: the primitive tests of a simulator's step in one call, spread over
/// `config.threads` threads. Counters are summed over the batch.
[[nodiscard]] std::vector<std::optional<double>> first_contact_times(
    std::span<const PrimitiveQuery> queries, PrimitiveCcdCounters* counters = nullptr,
    const PrimitiveCcdBatchConfig& config = {});

/// Where the pair touches at local time t (a point of the vertex, or the midpoint of the two
/// edges' closest points), in double precision.
[[nodiscard]] Eigen::Vector3d contact_point(ContactType type, const PrimitiveMotion& motion,
                                            double t);

}  // namespace kinray
