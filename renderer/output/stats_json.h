#pragma once
// The parts of every kinetic structure's --stats JSON that are written the same way: counters
// by their declared keys (kinetic/core/counters.h), events by kind with their total, and the four
// quality measures (kinetic/core/quality_measures.h).
#include <nlohmann/json.hpp>

#include "kinetic/core/quality_measures.h"

namespace kinray {

/// {"key": value, ...} for one section of a structure's counters: for_each(visit) calls
/// visit("stats key", value) for each of them (a KslStats::for_each_list_counter, say).
template <class ForEach>
[[nodiscard]] nlohmann::json section_json(ForEach&& for_each) {
  nlohmann::json out = nlohmann::json::object();
  for_each([&](const char* key, uint64_t value) { out[key] = value; });
  return out;
}

/// {"key": value, ...} for each counter of `counters` (a KINRAY_COUNTERS struct).
template <class Counters>
[[nodiscard]] nlohmann::json counters_json(const Counters& counters) {
  return section_json([&](auto visit) { counters.for_each_counter(visit); });
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
