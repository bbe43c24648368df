#include "renderer/shadows/lighting.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "renderer/shading.h"
#include "renderer/shadows/shadow_rays.h"
#include "util/parallel.h"

namespace kinray {
namespace {

/// One hit pixel of a row: its surface and the first of its shadow rays in the row's batch.
struct HitShadowRays {
  int i = 0;
  size_t first = 0;
  uint32_t traced = 0;  ///< bit l: light l faces the hit, its ray is in the batch
};

}  // namespace

Color lit_color(const SurfacePoint& surface, const Vec3& origin,
                const std::vector<CameraSpaceLight>& lights, uint32_t mask) {
  // The interpolated normal turned towards the eye (the visible side).
  const Eigen::Vector3f n =
      surface.normal.dot(surface.view) > 0 ? Eigen::Vector3f(-surface.normal) : surface.normal;
  Color irradiance = Color::Zero();
  for (size_t l = 0; l < lights.size(); ++l) {
    if (!(mask >> l & 1u)) continue;
    const Eigen::Vector3f to_light =
        unfold(lights[l].vector_from(origin), surface.tan_half_fov).normalized().cast<float>();
    irradiance += lights[l].color * std::max(0.0f, n.dot(to_light));
  }
  return surface.base.cwiseProduct(Color::Constant(kAmbient) + kDiffuse * irradiance);
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
  const PixelRays image{frame.width, frame.height};
  frame.lit.assign(frame.pixel_count(), 0u);
  parallel_for(size_t(frame.height), threads, [&](size_t row) {
    const int j = int(row);
    std::vector<LitHit> hits;
    std::vector<HitShadowRays> pixels;
    std::vector<ShadowRay> rays;
    RowTriangles triangles(scene, frame.time);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      if (frame.object[p] == kNoHit) {
        frame.color[p] = kBackgroundColor;
        continue;
      }
      const TriangleAtInstant& triangle = triangles.at(frame.object[p], frame.prim[p]);
      const Vec3 d = image.direction(i, j);
      const LitHit& hit =
          hits.emplace_back(lit_hit(triangle, d, view_direction(d, triangle.tan_half_fov)));
      HitShadowRays& pixel = pixels.emplace_back(HitShadowRays{i, rays.size(), 0u});
      for (size_t l = 0; l < at_t.size(); ++l)
        if (auto ray = shadow_ray(hit, at_t[l], frame.object[p], frame.prim[p])) {
          rays.push_back(*ray);
          pixel.traced |= 1u << l;
        }
    }
    std::vector<uint8_t> blocked(rays.size(), 0);
    if (!rays.empty()) tracer.occluded(rays, blocked);
    for (size_t k = 0; k < pixels.size(); ++k) {
      const HitShadowRays& pixel = pixels[k];
      uint32_t mask = 0;
      size_t r = pixel.first;
      for (size_t l = 0; l < at_t.size(); ++l)
        if (pixel.traced >> l & 1u)
          if (!blocked[r++]) mask |= 1u << l;
      const size_t p = frame.index(pixel.i, j);
      frame.lit[p] = mask;
      frame.color[p] = lit_color(hits[k], at_t, mask);
    }
  });
}

}  // namespace kinray
