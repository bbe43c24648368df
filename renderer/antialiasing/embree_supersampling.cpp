#include "renderer/antialiasing/embree_supersampling.h"

#include <limits>
#include <span>
#include <stdexcept>
#include <vector>

#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/flush_denormals.h"
#include "renderer/shading.h"
#include "renderer/shadows/embree_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "util/parallel.h"

namespace kinray {
namespace {

/// Embree's ray packets of width P.
template <int P>
struct Packet;
template <>
struct Packet<4> {
  using RayHit = RTCRayHit4;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
    rtcIntersect4(valid, s, c, r);
  }
};
template <>
struct Packet<8> {
  using RayHit = RTCRayHit8;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
    rtcIntersect8(valid, s, c, r);
  }
};
template <>
struct Packet<16> {
  using RayHit = RTCRayHit16;
  static void intersect(const int* valid, RTCScene s, RTCIntersectContext* c, RayHit* r) {
    rtcIntersect16(valid, s, c, r);
  }
};

/// The geometry and primitive ids the rays (x, y, 1) of `samples` hit: one ray at a time (P = 1)
/// or P at a time, the samples of one pixel being neighbours.
template <int P>
void trace(RTCScene scene, RTCIntersectContext& context, std::span<const Vec2> samples,
           std::span<RTCHit> hits) {
  if constexpr (P == 1) {
    for (size_t k = 0; k < samples.size(); ++k) {
      RTCRayHit rayhit{};
      rayhit.ray.dir_x = float(samples[k].x());
      rayhit.ray.dir_y = float(samples[k].y());
      rayhit.ray.dir_z = 1.0f;
      rayhit.ray.tfar = std::numeric_limits<float>::infinity();
      rayhit.ray.mask = ~0u;
      rayhit.hit.geomID = rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
      rtcIntersect1(scene, &context, &rayhit);
      hits[k] = rayhit.hit;
    }
  } else {
    for (size_t k0 = 0; k0 < samples.size(); k0 += P) {
      alignas(64) typename Packet<P>::RayHit rayhit{};
      alignas(64) int valid[P];
      for (size_t k = 0; k < size_t(P); ++k) {
        const bool used = k0 + k < samples.size();
        valid[k] = used ? -1 : 0;
        const Vec2& d = samples[used ? k0 + k : k0];
        rayhit.ray.dir_x[k] = float(d.x());
        rayhit.ray.dir_y[k] = float(d.y());
        rayhit.ray.dir_z[k] = 1.0f;
        rayhit.ray.tfar[k] = std::numeric_limits<float>::infinity();
        rayhit.ray.mask[k] = ~0u;
        rayhit.ray.id[k] = unsigned(k);
        rayhit.hit.geomID[k] = rayhit.hit.primID[k] = RTC_INVALID_GEOMETRY_ID;
      }
      Packet<P>::intersect(valid, scene, &context, &rayhit);
      for (size_t k = 0; k < size_t(P) && k0 + k < samples.size(); ++k) {
        hits[k0 + k].geomID = rayhit.hit.geomID[k];
        hits[k0 + k].primID = rayhit.hit.primID[k];
      }
    }
  }
}

}  // namespace

void embree_supersample(RTCScene scene, const CameraSpaceScene& camera_space,
                        const CameraSpaceLights* lights, int samples, int packet, int threads,
                        Frame& frame) {
  const int m = sample_grid_side(samples);
  if (m == 0) throw std::invalid_argument("embree_supersample: the sample count must be a square");
  if (packet != 1 && packet != 4 && packet != 8 && packet != 16)
    throw std::invalid_argument("embree_supersample: packets of 1, 4, 8 or 16 rays");
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
    const size_t n = size_t(samples);
    std::vector<Vec2> positions(n);
    std::vector<RTCHit> hits(n);
    const int j = int(row);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      const PixelSquare square = pixel_square(image, i, j);
      for (int k = 0; k < samples; ++k) positions[size_t(k)] = pixel_sample(square, p, k, m);
      switch (packet) {
        case 4:
          trace<4>(scene, context, positions, hits);
          break;
        case 8:
          trace<8>(scene, context, positions, hits);
          break;
        case 16:
          trace<16>(scene, context, positions, hits);
          break;
        default:
          trace<1>(scene, context, positions, hits);
          break;
      }
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (size_t k = 0; k < n; ++k) {
        const Vec2& s = positions[k];
        const Color c =
            hits[k].geomID == RTC_INVALID_GEOMETRY_ID
                ? kBackgroundColor
                : shade(hits[k].geomID, hits[k].primID, Vec3(s.x(), s.y(), 1.0), nullptr);
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
