#include "verification/coincident_fronts.h"

#include <algorithm>

#include "scenes/present_objects.h"
#include "util/pixel_rays.h"

namespace kinray {
namespace {

/// A margin beyond double rounding: a ray this far inside every edge of two triangles is inside
/// both (the margins of exact_hit are relative, and rounded by about 1e-16).
constexpr double kInside = 1e-12;

bool strictly_inside(const ExactHit& hit) {
  return std::all_of(hit.margin.begin(), hit.margin.end(), [](double m) { return m > kInside; });
}

/// Whether ray d is strictly inside two triangles at the depth of the nearest triangle it pierces
/// (inside or on its edges: a triangle the ray misses by less than the edge tolerance, a sliver
/// seen edge-on say, is no front). Two triangles of a mesh that share an edge or a vertex never
/// hold one ray strictly inside both, whatever their size; overlapping ones do, however thin (the
/// edge tolerance would miss slivers narrower than itself, which BART's car panels are when seen
/// from afar).
bool nearest_coincide(const std::vector<PresentObject>& objects, const CameraSpaceScene& scene,
                      const Vec3& d, const TieTolerance& tolerance, std::vector<ExactHit>& hits) {
  hits.clear();
  for (const PresentObject& o : objects) {
    if (!segment_may_meet_box(o, Vec3::Zero(), d, kInfinity)) continue;
    for (const Triangle& tri : scene.triangles(o.object)) {
      const ExactHit hit = exact_hit(
          {o.positions[tri[0]], o.positions[tri[1]], o.positions[tri[2]]}, d, tolerance.edge);
      if (hit.valid &&
          std::all_of(hit.margin.begin(), hit.margin.end(), [](double m) { return m >= 0; }))
        hits.push_back(hit);
    }
  }
  if (hits.size() < 2) return false;
  const ExactHit& nearest = *std::min_element(
      hits.begin(), hits.end(), [](const ExactHit& a, const ExactHit& b) { return a.z < b.z; });
  int inside = 0;
  for (const ExactHit& hit : hits)
    if (strictly_inside(hit) && same_depth(hit, nearest, tolerance)) ++inside;
  return inside >= 2;
}

}  // namespace

std::vector<uint8_t> coincident_fronts(const CameraSpaceScene& scene, const ShutterWindow& window,
                                       int width, int height, const std::vector<size_t>& candidates,
                                       int instants, const TieTolerance& tolerance) {
  std::vector<uint8_t> mask(size_t(width) * size_t(height), 0);
  if (candidates.empty()) return mask;
  const PixelRays image{width, height};
  std::vector<PresentObject> objects;
  std::vector<ExactHit> hits;
  for (int k = 0; k < instants; ++k) {
    place_present_objects(scene, window.open + window.length() * (k + 0.5) / instants, objects);
    for (size_t p : candidates)
      if (!mask[p] &&
          nearest_coincide(objects, scene,
                           image.direction(int(p % size_t(width)), int(p / size_t(width))),
                           tolerance, hits))
        mask[p] = 1;
  }
  return mask;
}

std::vector<uint8_t> coincident_fronts(const CameraSpaceScene& scene, const ShutterWindow& window,
                                       const Frame& tested, const Frame& reference) {
  std::vector<size_t> candidates;
  for (size_t p = 0; p < tested.color.size() && p < reference.color.size(); ++p)
    if ((tested.color[p] - reference.color[p]).cwiseAbs().maxCoeff() > kCoincidenceCandidateError)
      candidates.push_back(p);
  return coincident_fronts(scene, window, tested.width, tested.height, candidates);
}

}  // namespace kinray
