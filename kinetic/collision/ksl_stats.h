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

struct KslStats {
  KslEventCounts events;
  uint64_t certificates_computed = 0;  ///< every linear certificate (re)computation
  uint64_t certificates_live = 0;      ///< now: 1 per separated pair, 6 per watched pair
  uint64_t certificates_live_max = 0;  ///< the most live at once
  uint64_t list_pairs = 0;             ///< the front now: separated and overlapping leaf pairs
  uint64_t list_pairs_max = 0;
  uint64_t leaf_pairs = 0;       ///< overlapping triangle pairs listed now
  uint64_t watched_pairs = 0;    ///< overlapping inner pairs (watched for separation) now
  uint64_t leaf_tests = 0;       ///< (triangle pair, segment) primitive test runs
  uint64_t triangles = 0;        ///< of the trees (the structure's objects)

  KslStats& operator+=(const KslStats& o) {
    events += o.events;
    certificates_computed += o.certificates_computed;
    certificates_live += o.certificates_live;
    certificates_live_max += o.certificates_live_max;
    list_pairs += o.list_pairs;
    list_pairs_max += o.list_pairs_max;
    leaf_pairs += o.leaf_pairs;
    watched_pairs += o.watched_pairs;
    leaf_tests += o.leaf_tests;
    triangles += o.triangles;
    return *this;
  }
};

}  // namespace kinray
