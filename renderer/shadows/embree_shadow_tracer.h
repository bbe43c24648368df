#pragma once
// Shadow rays through the Embree backend's own scene: the geometries and float vertices that it
// traced the frame's primary rays through, queried with occlusion rays (rtcOccluded1, tnear 0,
// tfar = s_max). The triangle a ray leaves from is skipped by an occlusion filter installed on
// every geometry (the geometry id is the object index, the primitive id the triangle index), so
// the rule against self-intersection is the one of renderer/shadows/shadow_tracer.h.
#include <embree3/rtcore.h>

#include <atomic>

#include "renderer/shadows/shadow_tracer.h"

namespace kinray {

/// A shadow ray as Embree takes it (float, tnear 0, tfar = s_max), for rtcOccluded1.
[[nodiscard]] inline RTCRay embree_shadow_ray(const ShadowRay& in) {
  RTCRay ray{};
  ray.org_x = float(in.origin.x());
  ray.org_y = float(in.origin.y());
  ray.org_z = float(in.origin.z());
  ray.dir_x = float(in.direction.x());
  ray.dir_y = float(in.direction.y());
  ray.dir_z = float(in.direction.z());
  ray.tnear = 0.0f;
  ray.tfar = float(in.s_max);
  ray.mask = ~0u;
  return ray;
}

/// Whether `ray` meets a triangle of `scene` (whose geometries carry install_filter's filter)
/// other than its own, at Embree's ray time `time` (in [0, 1]; motion blur's time steps).
[[nodiscard]] bool embree_occluded(RTCScene scene, const ShadowRay& ray, float time = 0.0f);

/// Occlusion queries on the scene an Embree backend has committed for the current frame.
class EmbreeShadowTracer final : public ShadowTracer {
 public:
  /// Installs the filter that skips a ray's own triangle; call before committing `geometry`.
  static void install_filter(RTCGeometry geometry);
  /// The backend hands over the scene it committed for frame time t (it stays valid until the
  /// next bind).
  void bind(RTCScene scene, double t) {
    m_rtc_scene = scene;
    m_time = t;
  }

  [[nodiscard]] std::string name() const override { return "embree"; }
  /// Checks that the backend has committed its scene at t (the backend, not the tracer, moves
  /// the geometry); throws std::logic_error otherwise.
  void advance_to(double t) override;
  void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const override;
  void write_stats(nlohmann::json& stats) const override;

 private:
  RTCScene m_rtc_scene = nullptr;
  double m_time = 0;
  mutable std::atomic<uint64_t> m_rays{0}, m_blocked{0};
};

}  // namespace kinray
