#pragma once
// Counters of the kinetic separation list (kinetic_separation_list.h). Every event is set by the
// motion alone (a witness failing, a realizer changing, a segment beginning), none by how often
// one asks for contacts.
#include <cstdint>

#include "kinetic/core/counters.h"

namespace kinray {

// X(member, "stats key"), one line per kind of event.
#define KINRAY_KSL_EVENT_KINDS(X)                                                             \
  X(overlap, "overlap")       /* a separated pair began to overlap: its children listed */   \
  X(separation, "separation") /* an overlapping pair separated: its children removed */      \
  X(witness_change, "witness_change")   /* a separating axis failed; another took over */    \
  X(recertification, "recertification") /* a listed node's realizer changed */              \
  X(flightplan, "flightplan") /* a flightplan segment began: every certificate recomputed */ \
  X(rounding, "rounding")     /* a failure at the level of rounding: the same state holds */

struct KslEventCounts {
  KINRAY_EVENT_COUNTERS(KslEventCounts, KINRAY_KSL_EVENT_KINDS)
  /// Events that changed the separation list.
  [[nodiscard]] uint64_t external() const { return overlap + separation; }
};

// X(member, "stats key") of KslStats, by the section of --stats they are written in
// (kinetic/core/counters.h).
#define KINRAY_KSL_CERTIFICATE_COUNTERS(X)                                                    \
  X(certificates_computed, "computed") /* every linear certificate (re)computation */       \
  X(certificates_live, "live")         /* now: 1 per separated pair, 6 per watched pair */  \
  X(certificates_live_max, "live_max") /* the most live at once */
#define KINRAY_KSL_LIST_COUNTERS(X)                                                             \
  X(list_pairs, "pairs") /* the front now: separated and overlapping leaf pairs */              \
  X(list_pairs_max, "pairs_max")                                                                \
  X(leaf_pairs, "leaf_pairs")       /* overlapping triangle pairs listed now */                 \
  X(watched_pairs, "watched_pairs") /* overlapping inner pairs (watched for separation) */      \
  X(leaf_tests, "leaf_tests")       /* (triangle pair, segment) primitive test runs */          \
  X(apart_pairs, "apart_pairs") /* lazy trees: separated through the segment, no certificate */ \
  X(opened_at_keys, "opened_at_keys") /* lazy trees: pairs opened at a key rather than woken */
#define KINRAY_KSL_COUNTERS(X)         \
  KINRAY_KSL_CERTIFICATE_COUNTERS(X)   \
  KINRAY_KSL_LIST_COUNTERS(X)          \
  X(triangles, "triangles") /* of the trees (the structure's objects) */

struct KslStats {
  KINRAY_COUNTERS_WITH_EVENTS(KslStats, KslEventCounts, KINRAY_KSL_COUNTERS)
  /// visit("stats key", value) for the counters of the "certificates" section, of "list".
  KINRAY_COUNTER_SECTION(for_each_certificate_counter, KINRAY_KSL_CERTIFICATE_COUNTERS)
  KINRAY_COUNTER_SECTION(for_each_list_counter, KINRAY_KSL_LIST_COUNTERS)
};

}  // namespace kinray
