#pragma once
// The options every kinetic sort is constructed with: its events' kind, the audit, shared
// statistics, and the renewal of certificates at the end of their motion segments.
#include <cstdint>

#include "kinetic/sort/sort_stats.h"

namespace kinray {

struct KineticSortConfig {
  uint32_t event_kind = 0;  ///< EventKey.kind of every event of the structure
  bool audit = false;       ///< audit(now) after every handled event and every update
  /// When non-null the structure adds its counters here instead of keeping its own (many small
  /// instances, one total); stats() then returns this object.
  KineticSortStats* shared_stats = nullptr;
  /// A certificate that holds to the end of its motions' segment gets a renewal event there.
  /// An owner that recomputes every certificate of a switched motion at that instant, before any
  /// event of the structure at the same time, sets this false: the renewal would never be popped,
  /// only pushed, moved and cancelled.
  bool renew_at_segment_end = true;
};

}  // namespace kinray
