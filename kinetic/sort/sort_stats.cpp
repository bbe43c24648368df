#include "kinetic/sort/sort_stats.h"

namespace kinray {

QualityCounts quality_counts(const KineticSortStats& s, size_t objects) {
  QualityCounts q;
  q.certificates_live_max = s.certificates_live;
  q.certificates_live = s.certificates_live;
  q.certificates_computed = s.work;
  q.events = s.events() + s.events_renewal;
  q.events_internal = s.events_internal;
  q.events_external = s.events_external;
  q.objects_present = objects;
  return q;
}

}  // namespace kinray
