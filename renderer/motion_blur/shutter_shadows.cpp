#include "renderer/motion_blur/shutter_shadows.h"

#include <algorithm>
#include <bit>
#include <utility>

#include "renderer/backends/grid_meshes.h"
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
                                            std::vector<CameraSpaceLight>& scratch) const {
  Probe p;
  p.t = t;
  p.hit = lit_hit(m_scene, object, prim, d, t);
  const uint32_t skip = m_first_triangle.at(object) + prim;
  p.mask = light_mask(p.hit, lights_at(t, scratch), object, prim, [&](const ShadowRay& ray) {
    ++counts.shadow_rays;
    return m_tree.occluded(TreeRay{ray.origin, ray.direction, 0.0, ray.s_max, skip}, t);
  });
  return p;
}

bool ShutterShadows::reaches(uint32_t object, uint32_t prim, const Vec3& d, double t, size_t l,
                             ShutterShadowCounts& counts,
                             std::vector<CameraSpaceLight>& scratch) const {
  const LitHit hit = lit_hit(m_scene, object, prim, d, t);
  const auto ray = shadow_ray(hit, lights_at(t, scratch)[l], object, prim);
  if (!ray) return false;
  ++counts.shadow_rays;
  const uint32_t skip = m_first_triangle.at(object) + prim;
  return !m_tree.occluded(TreeRay{ray->origin, ray->direction, 0.0, ray->s_max, skip}, t);
}

uint32_t ShutterShadows::mask_at(uint32_t object, uint32_t prim, const Vec3& d, double t) const {
  ShutterShadowCounts counts;
  std::vector<CameraSpaceLight> scratch;
  return probe(object, prim, d, t, counts, scratch).mask;
}

void ShutterShadows::integrate(uint32_t object, uint32_t prim, const Vec3& d, double t0, double t1,
                               const GaussLegendre& shading, ColorAverage& average,
                               ShutterShadowCounts& counts) const {
  if (!(t1 > t0)) return;
  const double length = m_window.length();
  // The shading is smooth between the object's keys, not across them: the pieces between keys
  // each get the rule, as the headlight's integration does.
  std::vector<double> cuts{t0};
  for (double key : m_scene.objects[object].key_times)
    if (key > t0 && key < t1) cuts.push_back(key);
  cuts.push_back(t1);
  const size_t order = m_rule.nodes.size();
  std::vector<CameraSpaceLight> scratch;

  // 1. The masks at the ends and at every node.
  std::vector<Probe> probes;
  probes.reserve(2 + order * (cuts.size() - 1));
  probes.push_back(probe(object, prim, d, t0, counts, scratch));
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double middle = (cuts[c] + cuts[c + 1]) / 2, half = (cuts[c + 1] - cuts[c]) / 2;
    for (size_t k = 0; k < order; ++k) {
      Probe& p = probes.emplace_back(
          probe(object, prim, d, middle + half * m_rule.nodes[k], counts, scratch));
      p.weight = half / length * m_rule.weights[k];
    }
  }
  probes.push_back(probe(object, prim, d, t1, counts, scratch));
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
        (reaches(object, prim, d, mid, size_t(l), counts, scratch) == before ? lo : hi) = mid;
      }
      flips.emplace_back(lo + (hi - lo) / 2, 1u << l);
    }
  }
  std::sort(flips.begin(), flips.end());
  counts.mask_changes += flips.size();

  // 3. The pieces between keys and changes, each under its own mask, by the shading's rule.
  for (const auto& flip : flips) cuts.push_back(flip.first);
  std::sort(cuts.begin(), cuts.end());
  uint32_t mask = probes.front().mask;
  size_t next_flip = 0;
  for (size_t c = 0; c + 1 < cuts.size(); ++c) {
    const double a = cuts[c], b = cuts[c + 1];
    for (; next_flip < flips.size() && flips[next_flip].first <= a; ++next_flip)
      mask ^= flips[next_flip].second;
    if (!(b > a)) continue;
    const double middle = (a + b) / 2, half = (b - a) / 2;
    for (size_t k = 0; k < shading.nodes.size(); ++k) {
      const double t = middle + half * shading.nodes[k];
      average.add(lit_color(lit_hit(m_scene, object, prim, d, t), lights_at(t, scratch), mask),
                  half / length * shading.weights[k]);
    }
    counts.shading_nodes += shading.nodes.size();
  }
}

}  // namespace kinray
