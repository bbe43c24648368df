#include "renderer/shadows/lighting.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "renderer/shade_rows.h"
#include "renderer/shading.h"
#include "renderer/shadows/shadow_rays.h"

namespace kinray {
namespace {

/// One hit pixel of a row: its index and the first of its shadow rays in the row's batch.
struct HitShadowRays {
  size_t p = 0;
  size_t first = 0;
  uint32_t traced = 0;  ///< bit l: light l faces the hit, its ray is in the batch
};

/// A row of shade_frame_lit: each hit's shadow rays are gathered into one batch, traced when the
/// row ends, and the masks and colours written then.
class LitRow {
 public:
  LitRow(const std::vector<CameraSpaceLight>& lights, const ShadowTracer& tracer, Frame& frame)
      : m_lights(lights), m_tracer(tracer), m_frame(frame) {}

  void hit(size_t p, const TriangleAtInstant& triangle, const Vec3& d,
           const Eigen::Vector3f& view) {
    const LitHit& hit = m_hits.emplace_back(lit_hit(triangle, d, view));
    HitShadowRays& pixel = m_pixels.emplace_back(HitShadowRays{p, m_rays.size(), 0u});
    for (size_t l = 0; l < m_lights.size(); ++l)
      if (auto ray = shadow_ray(hit, m_lights[l], m_frame.object[p], m_frame.prim[p])) {
        m_rays.push_back(*ray);
        pixel.traced |= 1u << l;
      }
  }

  void finish() {
    std::vector<uint8_t> blocked(m_rays.size(), 0);
    if (!m_rays.empty()) m_tracer.occluded(m_rays, blocked);
    for (size_t k = 0; k < m_pixels.size(); ++k) {
      const HitShadowRays& pixel = m_pixels[k];
      uint32_t mask = 0;
      size_t r = pixel.first;
      for (size_t l = 0; l < m_lights.size(); ++l)
        if (pixel.traced >> l & 1u)
          if (!blocked[r++]) mask |= 1u << l;
      m_frame.lit[pixel.p] = mask;
      m_frame.color[pixel.p] = lit_color(m_hits[k], m_lights, mask);
    }
  }

 private:
  const std::vector<CameraSpaceLight>& m_lights;
  const ShadowTracer& m_tracer;
  Frame& m_frame;
  std::vector<LitHit> m_hits;
  std::vector<HitShadowRays> m_pixels;
  std::vector<ShadowRay> m_rays;
};

}  // namespace

Eigen::Vector3f visible_normal(const SurfacePoint& surface) {
  return surface.normal.dot(surface.view) > 0 ? Eigen::Vector3f(-surface.normal) : surface.normal;
}

float lambert_term(const Eigen::Vector3f& n, const SurfacePoint& surface, const Vec3& origin,
                   const CameraSpaceLight& light) {
  return n.dot(unfold(light.vector_from(origin), surface.tan_half_fov).normalized().cast<float>());
}

Color lit_color(const SurfacePoint& surface, const Vec3& origin,
                const std::vector<CameraSpaceLight>& lights, uint32_t mask) {
  const Eigen::Vector3f n = visible_normal(surface);
  Color irradiance = Color::Zero();
  for (size_t l = 0; l < lights.size(); ++l) {
    if (!(mask >> l & 1u)) continue;
    irradiance += lights[l].color * std::max(0.0f, lambert_term(n, surface, origin, lights[l]));
  }
  return surface.base.cwiseProduct(Color::Constant(kAmbient) + kDiffuse * irradiance);
}

uint32_t lit_side_mask(const SurfacePoint& surface, const Vec3& origin,
                       const std::vector<CameraSpaceLight>& lights) {
  const Eigen::Vector3f n = visible_normal(surface);
  uint32_t mask = 0;
  for (size_t l = 0; l < lights.size(); ++l)
    if (lambert_term(n, surface, origin, lights[l]) > 0.0f) mask |= 1u << l;
  return mask;
}

LitHit lit_hit(const TriangleAtInstant& triangle, const Vec3& d, const Eigen::Vector3f& view) {
  LitHit hit{surface_point(triangle, d, view)};
  const SurfacePoint& s = hit.surface;
  hit.origin = plane_hit(s.ray, s.p0, s.p1, s.p2);
  return hit;
}

LitHit lit_hit(const CameraSpaceScene& scene, uint32_t object, uint32_t prim, const Vec3& d,
               double t) {
  const TriangleAtInstant triangle =
      triangle_at_instant(scene, object, prim, shading_instant(scene, object, t));
  return lit_hit(triangle, d, view_direction(d, triangle.tan_half_fov));
}

void shade_frame_lit(const CameraSpaceScene& scene, const CameraSpaceLights& lights,
                     ShadowTracer& tracer, Frame& frame, int threads) {
  if (lights.empty() || lights.size() > kMaxLights)
    throw std::invalid_argument("shade_frame_lit: 1 to 32 lights");
  tracer.advance_to(frame.time);
  const std::vector<CameraSpaceLight> at_t = lights.at(frame.time);
  frame.lit.assign(frame.pixel_count(), 0u);
  shade_rows(scene, frame, threads, [&](int) { return LitRow(at_t, tracer, frame); });
}

}  // namespace kinray
