#pragma once
// The four quality measures of a kinetic structure (docs/design.md, "Vocabulary"; Basch, Guibas and
// Hershberger), defined once for every structure: compactness (live certificates, at most),
// responsiveness (certificates computed per event), locality (live certificates per object present)
// and efficiency (internal events per external one).
#include <algorithm>
#include <cstdint>

namespace kinray {

/// What the four measures are computed from.
struct QualityCounts {
  uint64_t certificates_live_max = 0, certificates_live = 0, certificates_computed = 0;
  uint64_t events = 0, events_internal = 0, events_external = 0;
  uint64_t objects_present = 0;  ///< the structure's objects (triangles, keys) present
};

struct QualityMeasures {
  uint64_t compactness = 0;   ///< the most live certificates at once
  double responsiveness = 0;  ///< certificate computations per event
  double locality = 0;        ///< live certificates per object present
  double efficiency = 0;      ///< internal events per external one (all internal: their count)
};

[[nodiscard]] inline QualityMeasures quality_measures(const QualityCounts& q) {
  const double events = double(q.events);
  const double objects = double(std::max<uint64_t>(q.objects_present, 1));
  QualityMeasures m;
  m.compactness = q.certificates_live_max;
  m.responsiveness = events > 0 ? double(q.certificates_computed) / events : 0.0;
  m.locality = double(q.certificates_live) / objects;
  m.efficiency = q.events_external > 0 ? double(q.events_internal) / double(q.events_external)
                                       : double(q.events_internal);
  return m;
}

}  // namespace kinray
