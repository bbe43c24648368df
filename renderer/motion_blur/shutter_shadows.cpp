#include "renderer/motion_blur/shutter_shadows.h"

#include <algorithm>
#include <bit>
#include <utility>

#include "renderer/backends/grid_meshes.h"
#include "renderer/motion_blur/texture_path.h"
#include "renderer/shadows/lighting.h"

namespace kinray {

struct ShutterShadows::Probe {
  double t = 0;
  double weight = 0;  ///< a node's share of the window; 0 at the interval's ends
  LitHit hit;
  uint32_t mask = 0;
};

ShutterShadows::ShutterShadows(const CameraSpaceScene& scene, const CameraSpaceLights& lights,
                               const GaussLegendre& rule)
    : m_scene(scene), m_lights(lights), m_rule(rule), m_tree(grid_meshes(scene)) {
  if (lights.still()) m_still_lights = lights.at(0);
  // The tree's meshes are the scene's objects in order (grid_meshes); a shadow ray skips its own
  // triangle by the tree's global id.
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    const uint32_t object = scene.objects[o].object;
    if (object >= m_first_triangle.size()) m_first_triangle.resize(object + 1, kNoNode);
    m_first_triangle[object] = m_tree.meshes().triangle_begin(uint32_t(o));
  }
}

const std::vector<CameraSpaceLight>& ShutterShadows::lights_at(
    double t, std::vector<CameraSpaceLight>& scratch) const {
  if (m_lights.still()) return m_still_lights;
  m_lights.at(t, scratch);
  return scratch;
}

void ShutterShadows::begin_window(const ShutterWindow& window) {
  m_window = window;
  m_tree.sweep(window.open, window.close);
}

ShutterShadows::Probe ShutterShadows::probe(uint32_t object, uint32_t prim, const Vec3& d, double t,
                                            ShutterShadowCounts& counts,
                                            std::vector<CameraSpaceLight>& scratch,
                                            OccluderHints& hints) const {
  Probe p;
  p.t = t;
  p.hit = lit_hit(m_scene, object, prim, d, t);
  const std::vector<CameraSpaceLight>& lights = lights_at(t, scratch);
  // Only lights whose Lambert term is positive: their shadow rays, and the shading's kink where
  // the term turns, are the mask's changes.
  p.mask = light_mask(
      p.hit, lights, object, prim,
      [&](const ShadowRay& ray, size_t l) { return blocked(ray, t, counts, hints[l]); },
      lit_side_mask(p.hit, lights));
  return p;
}

bool ShutterShadows::blocked(const ShadowRay& ray, double t, ShutterShadowCounts& counts,
                             uint32_t& hint) const {
  ++counts.shadow_rays;
  const uint32_t skip = m_first_triangle.at(ray.object) + ray.prim;
  const uint32_t found =
      m_tree.occluder(TreeRay{ray.origin, ray.direction, 0.0, ray.s_max, skip}, t, hint);
  if (found == kNoNode) return false;
  hint = found;
  return true;
}

bool ShutterShadows::reaches(uint32_t object, uint32_t prim, const Vec3& d, double t, size_t l,
                             ShutterShadowCounts& counts, std::vector<CameraSpaceLight>& scratch,
                             OccluderHints& hints) const {
  const LitHit hit = lit_hit(m_scene, object, prim, d, t);
  const std::vector<CameraSpaceLight>& lights = lights_at(t, scratch);
  if ((lit_side_mask(hit, lights) >> l & 1u) == 0) return false;
  const auto ray = shadow_ray(hit, lights[l], object, prim);
  return ray && !blocked(*ray, t, counts, hints[l]);
}

uint32_t ShutterShadows::mask_at(uint32_t object, uint32_t prim, const Vec3& d, double t) const {
  ShutterShadowCounts counts;
  std::vector<CameraSpaceLight> scratch;
  uint32_t hint = kNoNode;
  return light_mask(lit_hit(m_scene, object, prim, d, t), lights_at(t, scratch), object, prim,
                    [&](const ShadowRay& ray) { return blocked(ray, t, counts, hint); });
}

void ShutterShadows::integrate(uint32_t object, uint32_t prim, const Vec3& d, double t0, double t1,
                               const GaussLegendre& shading, ColorAverage& average,
                               ShutterShadowCounts& counts) const {
  if (!(t1 > t0)) return;
  const double length = m_window.length();
  const std::vector<double>& keys = m_scene.objects[object].key_times;
  std::vector<CameraSpaceLight> scratch;
  OccluderHints hints;
  hints.fill(kNoNode);

  // 1. The masks at the ends and at every node (of each piece between keys).
  std::vector<Probe> probes;
  probes.push_back(probe(object, prim, d, t0, counts, scratch, hints));
  for_each_quadrature_node(keys, m_rule, t0, t1, length, [&](double t, double w, size_t) {
    probes.emplace_back(probe(object, prim, d, t, counts, scratch, hints)).weight = w;
  });
  probes.push_back(probe(object, prim, d, t1, counts, scratch, hints));
  // In time order (the rule's nodes need not be): adjacent probes bracket the changes.
  std::sort(probes.begin(), probes.end(), [](const Probe& a, const Probe& b) { return a.t < b.t; });
  const bool steady = std::all_of(probes.begin(), probes.end(),
                                  [&](const Probe& p) { return p.mask == probes.front().mask; });
  if (steady && &shading == &m_rule) {
    // No light changed: the nodes' shadings are the integral's, as without shadows.
    for (size_t k = 1; k + 1 < probes.size(); ++k) {
      const Probe& p = probes[k];
      average.add(lit_color(p.hit, lights_at(p.t, scratch), p.mask), p.weight);
    }
    counts.shading_nodes += probes.size() - 2;
    return;
  }

  // 2. Each light that differs between adjacent probes changes once in between (as far as the
  // probes can tell): its time, bisected. (None when steady: the shading rule is another.)
  const double precision = kChangeTimePrecision * length;
  std::vector<std::pair<double, uint32_t>> flips;  // (time, the light's bit)
  for (size_t k = 0; k + 1 < probes.size(); ++k) {
    for (uint32_t differ = probes[k].mask ^ probes[k + 1].mask; differ != 0; differ &= differ - 1) {
      const int l = std::countr_zero(differ);
      const bool before = (probes[k].mask >> l & 1u) != 0;
      double lo = probes[k].t, hi = probes[k + 1].t;
      while (hi - lo > precision) {
        const double mid = lo + (hi - lo) / 2;
        if (!(mid > lo && mid < hi)) break;  // adjacent doubles
        (reaches(object, prim, d, mid, size_t(l), counts, scratch, hints) == before ? lo : hi) =
            mid;
      }
      flips.emplace_back(lo + (hi - lo) / 2, 1u << l);
    }
  }
  std::sort(flips.begin(), flips.end());
  counts.mask_changes += flips.size();

  // 3. The pieces between changes, each under its own mask, by the shading's rule (cut again at
  // the keys inside them).
  uint32_t mask = probes.front().mask;
  double a = t0;
  TexturePath texture(m_scene, object, prim, d);
  for (size_t f = 0; f <= flips.size(); ++f) {
    const double b = f < flips.size() ? flips[f].first : t1;
    if (b > a) {
      for_each_quadrature_cell(keys, shading, a, b, length,
                               [&](double t, double w, size_t, double lo, double hi) {
                                 LitHit hit = lit_hit(m_scene, object, prim, d, t);
                                 if (texture.textured()) hit.surface.base = texture.base(lo, hi);
                                 average.add(lit_color(hit, lights_at(t, scratch), mask), w);
                                 ++counts.shading_nodes;
                               });
      a = b;
    }
    if (f < flips.size()) mask ^= flips[f].second;
  }
}

}  // namespace kinray
