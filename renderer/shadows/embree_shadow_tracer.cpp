#include "renderer/shadows/embree_shadow_tracer.h"

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "renderer/flush_denormals.h"

namespace kinray {
namespace {

/// An intersect context that carries the triangle the current ray leaves from (Embree passes
/// the context to the filter, so it may be extended this way).
struct ShadowContext {
  RTCIntersectContext context;
  uint32_t skip_object = UINT32_MAX;
  uint32_t skip_prim = UINT32_MAX;
};

void skip_origin_triangle(const RTCFilterFunctionNArguments* args) {
  const auto* shadow = reinterpret_cast<const ShadowContext*>(args->context);
  for (unsigned k = 0; k < args->N; ++k) {
    if (args->valid[k] == 0) continue;
    if (RTCHitN_geomID(args->hit, args->N, k) == shadow->skip_object &&
        RTCHitN_primID(args->hit, args->N, k) == shadow->skip_prim)
      args->valid[k] = 0;
  }
}

}  // namespace

bool embree_occluded(RTCScene scene, const ShadowRay& ray, float time) {
  ShadowContext shadow;
  rtcInitIntersectContext(&shadow.context);
  RTCRay embree_ray = embree_shadow_ray(ray);
  embree_ray.time = time;
  shadow.skip_object = ray.object;
  shadow.skip_prim = ray.prim;
  rtcOccluded1(scene, &shadow.context, &embree_ray);
  // Embree sets tfar to -inf when the ray is occluded.
  return embree_ray.tfar < 0;
}

void EmbreeShadowTracer::install_filter(RTCGeometry geometry) {
  rtcSetGeometryOccludedFilterFunction(geometry, &skip_origin_triangle);
}

void EmbreeShadowTracer::advance_to(double t) {
  if (m_rtc_scene == nullptr || t != m_time)
    throw std::logic_error("EmbreeShadowTracer: the Embree backend has not traced frame time t");
}

void EmbreeShadowTracer::occluded(std::span<const ShadowRay> rays,
                                  std::span<uint8_t> blocked) const {
  const FlushDenormals flush_denormals;
  uint64_t count = 0;
  for (size_t r = 0; r < rays.size(); ++r) {
    blocked[r] = embree_occluded(m_rtc_scene, rays[r]) ? 1 : 0;
    count += blocked[r];
  }
  m_rays.fetch_add(rays.size(), std::memory_order_relaxed);
  m_blocked.fetch_add(count, std::memory_order_relaxed);
}

void EmbreeShadowTracer::write_stats(nlohmann::json& stats) const {
  stats["shadows"] = {{"tracer", name()}, {"rays", m_rays.load()}, {"blocked", m_blocked.load()}};
}

}  // namespace kinray
