#include "verification/shadow_diff.h"

#include <algorithm>
#include <cmath>

#include "renderer/shadows/brute_force_shadow_tracer.h"

namespace kinray {
namespace {

constexpr double kMinCos = 1e-3;

/// What one triangle says about a shadow ray: blocks it robustly, may block it within rounding,
/// or robustly not.
enum class Verdict { kBlocks, kMarginal, kClear };

Verdict judge(const ShadowRay& ray, const Vec3& p0, const Vec3& p1, const Vec3& p2,
              const ShadowTolerance& tolerance) {
  const ShadowCrossing c = cross_shadow_ray(ray, p0, p1, p2);
  const bool grazes = c.edge_margin <= tolerance.edge;
  if (!c.pierces && !grazes) return Verdict::kClear;
  if (!std::isfinite(c.s)) return grazes ? Verdict::kMarginal : Verdict::kClear;
  // Distances along the ray, in units of how far rounding moves the plane at this incidence.
  const double w = ray.direction.norm();
  const double cos = std::max(c.cos, kMinCos);
  const double o = ray.origin.norm();
  const bool near_start = std::abs(c.s) * w * cos <= tolerance.distance * (c.scale + o);
  bool near_end = false;
  if (std::isfinite(ray.s_max)) {
    const double light = (ray.origin + ray.s_max * ray.direction).norm();
    near_end = std::abs(ray.s_max - c.s) * w * cos <= tolerance.distance * (c.scale + light);
  }
  const bool inside = c.s > 0 && c.s < ray.s_max;
  if (!inside && !near_start && !near_end) return Verdict::kClear;
  if (c.pierces && inside && !grazes && !near_start && !near_end) return Verdict::kBlocks;
  return Verdict::kMarginal;
}

/// The class of a disagreement about light `light` at pixel (i, j), where both frames see
/// (object, prim); `positions` holds every object's camera-space positions at t (empty when it is
/// not present).
ShadowClass classify_shadow(const CameraSpaceScene& scene,
                            const std::vector<std::vector<Vec3>>& positions,
                            const CameraSpaceLight& light, const Vec3& d, uint32_t object,
                            uint32_t prim, const ShadowTolerance& tolerance) {
  const Triangle& tri = scene.triangles(object)[prim];
  const std::vector<Vec3>& own = positions[object];
  if (own.empty()) return ShadowClass::kReal;  // both name an object that is not there
  const Vec3 &p0 = own[tri[0]], &p1 = own[tri[1]], &p2 = own[tri[2]];
  const std::optional<ShadowRay> ray =
      shadow_ray(plane_hit(d, p0, p1, p2), d, p0, p1, p2, light, object, prim);
  // Both frames make the same ray from the same triangle: a light behind the surface was called
  // lit by one of them without a ray.
  if (!ray) return ShadowClass::kReal;
  bool marginal = false;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const std::vector<Triangle>& triangles = scene.triangles(o);
    const std::vector<Vec3>& at = positions[o];
    if (at.empty()) continue;
    for (uint32_t f = 0; f < triangles.size(); ++f) {
      if (o == object && f == prim) continue;
      const Triangle& g = triangles[f];
      const Verdict verdict = judge(*ray, at[g[0]], at[g[1]], at[g[2]], tolerance);
      if (verdict == Verdict::kBlocks) return ShadowClass::kReal;
      marginal |= verdict == Verdict::kMarginal;
    }
  }
  return marginal ? ShadowClass::kTie : ShadowClass::kReal;
}

}  // namespace

ShadowDiff compare_shadows(const CameraSpaceScene& scene, const CameraSpaceLights& lights,
                           const Frame& tested, const Frame& reference,
                           const ShadowTolerance& tolerance) {
  ShadowDiff diff;
  diff.pixels.assign(tested.pixel_count(), -1);
  // A frame read back from files (regression references) has no masks: nothing to compare.
  if (tested.lit.size() != tested.pixel_count() || reference.lit.size() != reference.pixel_count())
    return diff;
  diff.lights.resize(lights.size());
  const std::vector<CameraSpaceLight> at_t = lights.at(tested.time);
  const PixelRays image{tested.width, tested.height};
  std::vector<std::vector<Vec3>> positions(scene.objects.size());
  bool loaded = false;
  for (int j = 0; j < tested.height; ++j)
    for (int i = 0; i < tested.width; ++i) {
      const size_t p = tested.index(i, j);
      const uint32_t differ = tested.lit[p] ^ reference.lit[p];
      if (differ == 0 || tested.object[p] == kNoHit || tested.object[p] != reference.object[p] ||
          tested.prim[p] != reference.prim[p])
        continue;
      for (size_t l = 0; l < at_t.size(); ++l) {
        if (!(differ >> l & 1u)) continue;
        if (!loaded) {  // only frames that disagree somewhere pay for the positions
          for (size_t o = 0; o < scene.objects.size(); ++o)
            if (scene.objects[o].visible(tested.time))
              scene.objects[o].positions_at(tested.time, positions[o]);
          loaded = true;
        }
        const ShadowClass c = classify_shadow(scene, positions, at_t[l], image.direction(i, j),
                                              tested.object[p], tested.prim[p], tolerance);
        ++(c == ShadowClass::kReal ? diff.lights[l].real : diff.lights[l].tie);
        diff.pixels[p] = std::max(diff.pixels[p], int8_t(c));
      }
    }
  return diff;
}

}  // namespace kinray
