#pragma once
// The parts of every kinetic structure's --stats JSON that are written the same way: counters
// by their declared keys (kinetic/core/counters.h), events by kind with their total, and the four
// quality measures (kinetic/core/quality_measures.h).
#include <nlohmann/json.hpp>

#include "kinetic/core/quality_measures.h"

namespace kinray {

/// {"key": value, ...} for each counter of `counters` (a KINRAY_COUNTERS struct).
template <class Counters>
[[nodiscard]] nlohmann::json counters_json(const Counters& counters) {
  nlohmann::json out = nlohmann::json::object();
  counters.for_each_counter([&](const char* key, uint64_t value) { out[key] = value; });
  return out;
}

/// counters_json of a KINRAY_EVENT_COUNTERS struct, with "total".
template <class EventCounts>
[[nodiscard]] nlohmann::json event_counts_json(const EventCounts& events) {
  nlohmann::json out = counters_json(events);
  out["total"] = events.total();
  return out;
}

/// {"compactness", "responsiveness", "locality", "efficiency"}.
[[nodiscard]] inline nlohmann::json quality_json(const QualityCounts& counts) {
  const QualityMeasures q = quality_measures(counts);
  return {{"compactness", q.compactness},
          {"responsiveness", q.responsiveness},
          {"locality", q.locality},
          {"efficiency", q.efficiency}};
}

}  // namespace kinray
