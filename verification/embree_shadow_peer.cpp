#include "verification/embree_shadow_peer.h"

#include <embree3/rtcore.h>

#include <chrono>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <vector>

#include "renderer/shadows/embree_shadow_tracer.h"

namespace kinray {

namespace {

/// The intersect context with the triangle a ray leaves from, for the filter.
struct SkipContext {
  RTCIntersectContext context;
  unsigned geometry = RTC_INVALID_GEOMETRY_ID, primitive = RTC_INVALID_GEOMETRY_ID;
};

void skip_origin_triangle(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const SkipContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    if (RTCHitN_geomID(args->hit, args->N, i) == ctx->geometry &&
        RTCHitN_primID(args->hit, args->N, i) == ctx->primitive)
      args->valid[i] = 0;
  }
}

RTCDevice shared_device() {
  static const RTCDevice device = [] {
    // One thread: shadow rays are traced by the caller's thread, and the benchmark compares the
    // structures' updates on one core each.
    RTCDevice d = rtcNewDevice("threads=1");
    if (!d) throw std::runtime_error("cannot create an Embree device for shadow rays");
    return d;
  }();
  return device;
}

class EmbreeShadowPeer final : public ShadowTracer {
 public:
  EmbreeShadowPeer(const CameraSpaceScene& scene, bool refit) : m_scene(scene), m_refit(refit) {
    m_vertices.resize(scene.objects.size(), nullptr);
    m_geometries.resize(scene.objects.size(), nullptr);
    m_present.assign(scene.objects.size(), 1);
  }
  ~EmbreeShadowPeer() override {
    if (m_rtc_scene) rtcReleaseScene(m_rtc_scene);
    for (RTCGeometry g : m_geometries)
      if (g) rtcReleaseGeometry(g);
  }
  EmbreeShadowPeer(const EmbreeShadowPeer&) = delete;
  EmbreeShadowPeer& operator=(const EmbreeShadowPeer&) = delete;

  [[nodiscard]] std::string name() const override {
    return m_refit ? "embree-refit" : "embree-rebuild";
  }

  void advance_to(double t) override {
    const auto start = std::chrono::steady_clock::now();
    const bool first = m_rtc_scene == nullptr;
    if (first || !m_refit) {
      if (m_rtc_scene) rtcReleaseScene(m_rtc_scene);
      m_rtc_scene = rtcNewScene(shared_device());
      rtcSetSceneFlags(m_rtc_scene, RTCSceneFlags(RTC_SCENE_FLAG_ROBUST |
                                                  RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION |
                                                  (m_refit ? RTC_SCENE_FLAG_DYNAMIC : 0)));
      if (m_refit) rtcSetSceneBuildQuality(m_rtc_scene, RTC_BUILD_QUALITY_LOW);
    }
    for (size_t o = 0; o < m_scene.objects.size(); ++o) {
      const CameraSpaceObject& cs = m_scene.objects[o];
      const auto& triangles = m_scene.triangles(o);
      if (triangles.empty() || cs.vertex_count == 0) continue;
      if (!m_geometries[o]) {
        RTCGeometry g = rtcNewGeometry(shared_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, triangles.data(),
                                   0, sizeof(Triangle), triangles.size());
        m_vertices[o] = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), cs.vertex_count));
        rtcSetGeometryBuildQuality(
            g, m_refit && !cs.is_static ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_MEDIUM);
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
      if (first || !m_refit) rtcAttachGeometryByID(m_rtc_scene, m_geometries[o], unsigned(o));
    }
    rtcCommitScene(m_rtc_scene);
    m_update_s += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++m_frames;
  }

  void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const override {
    for (size_t i = 0; i < rays.size(); ++i) {
      const ShadowRay& r = rays[i];
      SkipContext ctx;
      rtcInitIntersectContext(&ctx.context);
      ctx.context.filter = &skip_origin_triangle;
      ctx.geometry = object_geometry(r.object);
      ctx.primitive = r.prim;
      RTCRay ray = embree_shadow_ray(r);
      rtcOccluded1(m_rtc_scene, &ctx.context, &ray);
      blocked[i] = ray.tfar < 0 ? 1 : 0;  // Embree marks an occluded ray with tfar = -inf
    }
  }

  void write_stats(nlohmann::json& stats) const override {
    stats["shadow_tree"] = {
        {"kind", name()}, {"frames", m_frames}, {"time_s", {{"update", m_update_s}}}};
  }

 private:
  /// Geometries are attached by object index in the camera-space scene.
  [[nodiscard]] unsigned object_geometry(uint32_t object) const {
    for (size_t o = 0; o < m_scene.objects.size(); ++o)
      if (m_scene.objects[o].object == object) return unsigned(o);
    return RTC_INVALID_GEOMETRY_ID;
  }

  const CameraSpaceScene& m_scene;
  bool m_refit = false;
  RTCScene m_rtc_scene = nullptr;
  std::vector<RTCGeometry> m_geometries;
  std::vector<float*> m_vertices;
  std::vector<uint8_t> m_present;
  std::vector<Vec3> m_positions;
  uint64_t m_frames = 0;
  double m_update_s = 0;
};

}  // namespace

std::unique_ptr<ShadowTracer> make_embree_shadow_tracer(const CameraSpaceScene& scene, bool refit) {
  return std::make_unique<EmbreeShadowPeer>(scene, refit);
}

}  // namespace kinray
