#pragma once
// The four quality measures of a kinetic structure (DESIGN.md, Basch-Guibas-Hershberger), defined
// once for every structure's --stats: compactness (live certificates, at most), responsiveness
// (certificates computed per event), locality (live certificates per object present) and
// efficiency (internal events per external one).
#include <algorithm>
#include <cstdint>

#include <nlohmann/json.hpp>

namespace kinray {

/// What the four measures are computed from.
struct QualityCounts {
  uint64_t certificates_live_max = 0, certificates_live = 0, certificates_computed = 0;
  uint64_t events = 0, events_internal = 0, events_external = 0;
  uint64_t objects_present = 0;  ///< triangles present (the structure's objects)
};

/// {"compactness", "responsiveness", "locality", "efficiency"}.
[[nodiscard]] inline nlohmann::json quality_json(const QualityCounts& q) {
  const double events = double(q.events);
  const double objects = double(std::max<uint64_t>(q.objects_present, 1));
  return {
      {"compactness", q.certificates_live_max},
      {"responsiveness", events > 0 ? double(q.certificates_computed) / events : 0.0},
      {"locality", double(q.certificates_live) / objects},
      {"efficiency", q.events_external > 0 ? double(q.events_internal) / double(q.events_external)
                                           : double(q.events_internal)},
  };
}

}  // namespace kinray
