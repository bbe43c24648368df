#include "renderer/antialiasing/embree_supersampling.h"

#include <limits>
#include <stdexcept>
#include <vector>

#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/flush_denormals.h"
#include "renderer/shading.h"
#include "renderer/shadows/embree_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "util/parallel.h"

namespace kinray {

void embree_supersample(RTCScene scene, const CameraSpaceScene& camera_space,
                        const CameraSpaceLights* lights, int samples, int threads, Frame& frame) {
  const int m = sample_grid_side(samples);
  if (m == 0) throw std::invalid_argument("embree_supersample: the sample count must be a square");
  if (lights != nullptr && lights->empty()) lights = nullptr;
  const PixelRays image{frame.width, frame.height};
  const std::vector<CameraSpaceLight> at_t =
      lights ? lights->at(frame.time) : std::vector<CameraSpaceLight>{};
  if (lights) frame.lit.assign(frame.pixel_count(), 0u);
  auto occluded = [&](const ShadowRay& ray) { return embree_occluded(scene, ray); };

  parallel_for_dynamic(size_t(frame.height), threads, [&](size_t row) {
    const FlushDenormals flush_denormals;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;  // the rays of one pixel are neighbours
    RowTriangles triangles(camera_space, frame.time);
    // The colour of the ray d on (object, prim), as shade_frame or shade_frame_lit colours a
    // centre ray on it.
    auto shade = [&](uint32_t object, uint32_t prim, const Vec3& d, uint32_t* mask) -> Color {
      const TriangleAtInstant& triangle = triangles.at(object, prim);
      const Eigen::Vector3f view = view_direction(d, triangle.tan_half_fov);
      if (!lights) return headlight_color(triangle, d, view);
      const LitHit hit = lit_hit(triangle, d, view);
      const uint32_t lit = light_mask(hit, at_t, object, prim, occluded);
      if (mask) *mask = lit;
      return lit_color(hit, at_t, lit);
    };
    const int j = int(row);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      const PixelSquare square = pixel_square(image, i, j);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = 0; k < samples; ++k) {
        const Vec2 s = pixel_sample(square, p, k, m);
        RTCRayHit rayhit{};
        rayhit.ray.dir_x = float(s.x());
        rayhit.ray.dir_y = float(s.y());
        rayhit.ray.dir_z = 1.0f;
        rayhit.ray.tfar = std::numeric_limits<float>::infinity();
        rayhit.ray.mask = ~0u;
        rayhit.hit.geomID = rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &context, &rayhit);
        const Color c =
            rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID
                ? kBackgroundColor
                : shade(rayhit.hit.geomID, rayhit.hit.primID, Vec3(s.x(), s.y(), 1.0), nullptr);
        sum += c.cast<double>();
      }
      frame.color[p] = (sum / samples).cast<float>();
      if (lights && frame.object[p] != kNoHit) {
        uint32_t mask = 0;
        (void)shade(frame.object[p], frame.prim[p], image.direction(i, j), &mask);
        frame.lit[p] = mask;
      }
    }
  });
}

}  // namespace kinray
