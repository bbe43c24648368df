#include "scenes/present_objects.h"

#include <algorithm>
#include <cmath>

namespace kinray {

void place_present_objects(const CameraSpaceScene& scene, double t,
                           std::vector<PresentObject>& out) {
  out.clear();
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const CameraSpaceObject& cs = scene.objects[o];
    if (!cs.visible(t) || scene.triangles(o).empty()) continue;
    PresentObject& present = out.emplace_back();
    present.object = uint32_t(o);
    cs.positions_at(t, present.positions);
    present.lo = present.hi = present.positions.front();
    for (const Vec3& p : present.positions) {
      present.lo = present.lo.cwiseMin(p);
      present.hi = present.hi.cwiseMax(p);
    }
  }
}

bool segment_may_meet_box(const PresentObject& object, const Vec3& origin, const Vec3& direction,
                          double s_max) {
  double s_lo = 0, s_hi = s_max;
  for (int a = 0; a < 3; ++a) {
    const double pad = 1e-9 * (std::abs(object.lo[a]) + std::abs(object.hi[a]) + 1e-300);
    const double lo = object.lo[a] - pad - origin[a], hi = object.hi[a] + pad - origin[a];
    const double w = direction[a];
    if (w == 0) {
      if (lo > 0 || hi < 0) return false;
      continue;
    }
    const double a0 = lo / w, a1 = hi / w;
    s_lo = std::max(s_lo, std::min(a0, a1));
    s_hi = std::min(s_hi, std::max(a0, a1));
    if (s_lo > s_hi * (1 + 1e-12) + 1e-300) return false;
  }
  return true;
}

}  // namespace kinray
