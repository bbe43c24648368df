#pragma once
// The counters of a kinetic sort (one structure's, or many small ones' shared total), declared
// once (kinetic/core/counters.h), and the quality measures computed from them.
#include <cstddef>
#include <cstdint>

#include "kinetic/core/counters.h"
#include "kinetic/core/quality_measures.h"

namespace kinray {

// X(member, "stats key") of KineticSortStats.
#define KINRAY_SORT_COUNTERS(X)                                                              \
  X(events_internal, "events_internal") /* failures that did not change the front */        \
  X(events_external, "events_external") /* failures that changed the front */              \
  X(events_renewal, "events_renewal")   /* at a certificate's end, or spurious: no change */ \
  X(certificates_live, "certificates_live")       /* held now (a gauge) */                  \
  X(certificates_created, "certificates_created") /* computed and (re)scheduled */          \
  X(work, "work")             /* certificate computations, comparisons included */          \
  X(degenerate, "degenerate") /* near-ties resolved by the same-instant guard */             \
  X(exact_deferred, "exact_deferred") /* exact failure searches put off to a recheck */

/// Counters of one structure (or of many, when shared).
struct KineticSortStats {
  KINRAY_COUNTERS(KineticSortStats, KINRAY_SORT_COUNTERS)
  [[nodiscard]] uint64_t events() const { return events_internal + events_external; }
};

/// What the quality measures of a sort over `objects` keys are computed from. The sorts keep
/// no maximum of their live certificates: compactness is the count held now.
[[nodiscard]] QualityCounts quality_counts(const KineticSortStats& stats, size_t objects);

}  // namespace kinray
