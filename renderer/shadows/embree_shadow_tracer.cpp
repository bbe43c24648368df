#include "renderer/shadows/embree_shadow_tracer.h"

#include <chrono>
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

RTCDevice owned_scene_device() {
  static const RTCDevice device = [] {
    // One thread: shadow rays are traced by the caller's thread, and the benchmark compares the
    // structures' updates on one core each.
    RTCDevice d = rtcNewDevice("threads=1");
    if (!d) throw std::runtime_error("cannot create an Embree device for shadow rays");
    return d;
  }();
  return device;
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

EmbreeShadowTracer::EmbreeShadowTracer(const CameraSpaceScene& scene, Update update)
    : m_scene(&scene), m_refit(update == Update::kRefit) {
  m_vertices.resize(scene.objects.size(), nullptr);
  m_geometries.resize(scene.objects.size(), nullptr);
  m_present.assign(scene.objects.size(), 1);
}

EmbreeShadowTracer::~EmbreeShadowTracer() {
  if (m_scene == nullptr) return;  // a bound scene belongs to the backend
  if (m_rtc_scene) rtcReleaseScene(m_rtc_scene);
  for (RTCGeometry g : m_geometries)
    if (g) rtcReleaseGeometry(g);
}

std::string EmbreeShadowTracer::name() const {
  if (m_scene == nullptr) return "embree";
  return m_refit ? "embree-refit" : "embree-rebuild";
}

void EmbreeShadowTracer::advance_to(double t) {
  if (m_scene != nullptr) {
    update_owned(t);
    return;
  }
  if (m_rtc_scene == nullptr || t != m_time)
    throw std::logic_error("EmbreeShadowTracer: the Embree backend has not traced frame time t");
}

void EmbreeShadowTracer::update_owned(double t) {
  const auto start = std::chrono::steady_clock::now();
  const RTCDevice device = owned_scene_device();
  const bool first = m_rtc_scene == nullptr;
  if (first || !m_refit) {
    if (m_rtc_scene) rtcReleaseScene(m_rtc_scene);
    m_rtc_scene = rtcNewScene(device);
    rtcSetSceneFlags(m_rtc_scene,
                     RTCSceneFlags(RTC_SCENE_FLAG_ROBUST | (m_refit ? RTC_SCENE_FLAG_DYNAMIC : 0)));
    if (m_refit) rtcSetSceneBuildQuality(m_rtc_scene, RTC_BUILD_QUALITY_LOW);
  }
  for (size_t o = 0; o < m_scene->objects.size(); ++o) {
    const CameraSpaceObject& cs = m_scene->objects[o];
    const auto& triangles = m_scene->triangles(o);
    if (triangles.empty() || cs.vertex_count == 0) continue;
    if (!m_geometries[o]) {
      RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
      rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles.data(), 0,
                                 sizeof(Triangle), triangles.size());
      m_vertices[o] = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), cs.vertex_count));
      rtcSetGeometryBuildQuality(
          g, m_refit && !cs.is_static ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_MEDIUM);
      install_filter(g);
      m_geometries[o] = g;
    }
    bool changed = first || !m_refit;
    if (first || !cs.is_static) {
      changed = true;
      cs.positions_at(t, m_positions);
      for (size_t v = 0; v < cs.vertex_count; ++v)
        for (int c = 0; c < 3; ++c) m_vertices[o][3 * v + size_t(c)] = float(m_positions[v][c]);
      rtcUpdateGeometryBuffer(m_geometries[o], RTC_BUFFER_TYPE_VERTEX, 0);
    }
    const bool present = cs.visible(t);
    if (present != (m_present[o] != 0) || first) {
      (present ? rtcEnableGeometry : rtcDisableGeometry)(m_geometries[o]);
      m_present[o] = present;
      changed = true;
    }
    if (changed) rtcCommitGeometry(m_geometries[o]);
    // The geometry id is the object index (CameraSpaceScene::build numbers objects by index).
    if (first || !m_refit) rtcAttachGeometryByID(m_rtc_scene, m_geometries[o], cs.object);
  }
  rtcCommitScene(m_rtc_scene);
  m_time = t;
  m_update_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++m_frames;
}

uint64_t EmbreeShadowTracer::trace(std::span<const ShadowRay> rays,
                                   std::span<uint8_t> blocked) const {
  uint64_t count = 0;
  for (size_t r = 0; r < rays.size(); ++r) {
    blocked[r] = embree_occluded(m_rtc_scene, rays[r]) ? 1 : 0;
    count += blocked[r];
  }
  return count;
}

void EmbreeShadowTracer::occluded(std::span<const ShadowRay> rays,
                                  std::span<uint8_t> blocked) const {
  uint64_t count = 0;
  if (m_scene != nullptr) {
    // The owned scene is traced under the caller's floating-point mode, as the benchmark's
    // kinetic trees are.
    count = trace(rays, blocked);
  } else {
    const FlushDenormals flush_denormals;
    count = trace(rays, blocked);
  }
  m_rays.fetch_add(rays.size(), std::memory_order_relaxed);
  m_blocked.fetch_add(count, std::memory_order_relaxed);
}

void EmbreeShadowTracer::write_stats(nlohmann::json& stats) const {
  if (m_scene != nullptr) {
    stats["shadow_tree"] = {
        {"kind", name()}, {"frames", m_frames}, {"time_s", {{"update", m_update_s}}}};
    return;
  }
  stats["shadows"] = {{"tracer", name()}, {"rays", m_rays.load()}, {"blocked", m_blocked.load()}};
}

}  // namespace kinray
