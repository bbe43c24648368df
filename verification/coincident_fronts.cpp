#include "verification/coincident_fronts.h"

#include <algorithm>
#include <array>

#include "util/pixel_rays.h"

namespace kinray {
namespace {

/// One object at an instant: its camera-space positions and their box.
struct ObjectAt {
  size_t index = 0;
  std::vector<Vec3> positions;
  Vec3 lo = Vec3::Zero(), hi = Vec3::Zero();
};

/// Whether the ray from the eye along d meets the box [lo, hi] at a positive parameter.
bool ray_meets_box(const Vec3& d, const Vec3& lo, const Vec3& hi) {
  double near = 0, far = kInfinity;
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0) {
      if (lo[a] > 0 || hi[a] < 0) return false;
      continue;
    }
    double t0 = lo[a] / d[a], t1 = hi[a] / d[a];
    if (t0 > t1) std::swap(t0, t1);
    near = std::max(near, t0);
    far = std::min(far, t1);
    if (near > far) return false;
  }
  return true;
}

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
bool nearest_coincide(const std::vector<ObjectAt>& objects, const CameraSpaceScene& scene,
                      const Vec3& d, const TieTolerance& tolerance, std::vector<ExactHit>& hits) {
  hits.clear();
  for (const ObjectAt& o : objects) {
    if (!ray_meets_box(d, o.lo, o.hi)) continue;
    for (const Triangle& tri : scene.triangles(o.index)) {
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
  std::vector<ObjectAt> objects;
  std::vector<ExactHit> hits;
  for (int k = 0; k < instants; ++k) {
    const double t = window.open + window.length() * (k + 0.5) / instants;
    objects.clear();
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      const CameraSpaceObject& object = scene.objects[o];
      if (!object.visible(t) || object.vertex_count == 0) continue;
      ObjectAt& at = objects.emplace_back();
      at.index = o;
      object.positions_at(t, at.positions);
      at.lo = at.hi = at.positions.front();
      for (const Vec3& p : at.positions) {
        at.lo = at.lo.cwiseMin(p);
        at.hi = at.hi.cwiseMax(p);
      }
    }
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
