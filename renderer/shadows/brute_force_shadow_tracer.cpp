#include "renderer/shadows/brute_force_shadow_tracer.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace kinray {

ShadowCrossing cross_shadow_ray(const ShadowRay& ray, const Vec3& p0, const Vec3& p1,
                                const Vec3& p2) {
  const Vec3& w = ray.direction;
  const Vec3& o = ray.origin;
  const Vec3 q0 = p0 - o, q1 = p1 - o, q2 = p2 - o;
  const double e01 = q0.cross(q1).dot(w), e12 = q1.cross(q2).dot(w), e20 = q2.cross(q0).dot(w);
  ShadowCrossing crossing;
  // Rounding p, q and o by a relative u moves E_pq(w) by at most
  // u |w| (|p| |q - o| + |q| |p - o| + |o| (|p - o| + |q - o|)): the margin is |E_pq| in units of
  // that bound (without u), whatever the sizes and distances.
  const double w_norm = w.norm(), o_norm = o.norm();
  const double a0 = p0.norm(), a1 = p1.norm(), a2 = p2.norm();
  const double r0 = q0.norm(), r1 = q1.norm(), r2 = q2.norm();
  const auto margin = [&](double e, double pa, double pr, double qa, double qr) {
    const double scale = w_norm * (pa * qr + qa * pr + o_norm * (pr + qr));
    return scale > 0 ? std::abs(e) / scale : 0.0;
  };
  crossing.edge_margin = std::min(
      {margin(e01, a0, r0, a1, r1), margin(e12, a1, r1, a2, r2), margin(e20, a2, r2, a0, r0)});
  const double sum = e01 + e12 + e20;  // = ((p1 - p0) x (p2 - p0)) . w
  crossing.s = q0.dot(q1.cross(q2)) / sum;
  // |cos| of the angle between the ray and the triangle's normal.
  const double normal_norm = (p1 - p0).cross(p2 - p0).norm();
  crossing.cos = normal_norm > 0 && w_norm > 0 ? std::abs(sum) / (normal_norm * w_norm) : 0.0;
  crossing.scale = std::max({a0, a1, a2});
  const bool same_sign = (e01 >= 0 && e12 >= 0 && e20 >= 0) || (e01 <= 0 && e12 <= 0 && e20 <= 0);
  crossing.pierces = same_sign && sum != 0;
  crossing.hit = crossing.pierces && crossing.s > 0 && crossing.s < ray.s_max;
  return crossing;
}

BruteForceShadowTracer::BruteForceShadowTracer(const CameraSpaceScene& scene) : m_scene(scene) {}

void BruteForceShadowTracer::advance_to(double t) {
  if (t < m_time) throw std::logic_error("BruteForceShadowTracer: frame times must not decrease");
  m_time = t;
  place_present_objects(m_scene, t, m_present);
}

bool BruteForceShadowTracer::blocks(const PresentObject& object, const ShadowRay& ray) const {
  if (!segment_may_meet_box(object, ray.origin, ray.direction, ray.s_max)) return false;
  const std::vector<Triangle>& triangles = m_scene.triangles(object.object);
  m_triangle_tests.fetch_add(triangles.size(), std::memory_order_relaxed);
  for (uint32_t f = 0; f < triangles.size(); ++f) {
    if (object.object == ray.object && f == ray.prim) continue;
    const Triangle& tri = triangles[f];
    if (cross_shadow_ray(ray, object.positions[tri[0]], object.positions[tri[1]],
                         object.positions[tri[2]])
            .hit)
      return true;
  }
  return false;
}

void BruteForceShadowTracer::occluded(std::span<const ShadowRay> rays,
                                      std::span<uint8_t> blocked) const {
  uint64_t count = 0;
  for (size_t r = 0; r < rays.size(); ++r) {
    blocked[r] = 0;
    for (const PresentObject& object : m_present)
      if (blocks(object, rays[r])) {
        blocked[r] = 1;
        ++count;
        break;
      }
  }
  m_rays.fetch_add(rays.size(), std::memory_order_relaxed);
  m_blocked.fetch_add(count, std::memory_order_relaxed);
}

void BruteForceShadowTracer::write_stats(nlohmann::json& stats) const {
  stats["shadows"] = {{"tracer", name()},
                      {"rays", m_rays.load()},
                      {"blocked", m_blocked.load()},
                      {"triangle_tests", m_triangle_tests.load()}};
}

}  // namespace kinray
