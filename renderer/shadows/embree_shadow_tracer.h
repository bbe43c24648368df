#pragma once
// Shadow rays through Embree (rtcOccluded1, tnear 0, tfar = s_max), on one of two scenes:
// - bound: the scene an Embree backend committed for the frame, the geometries and float vertices
//   that it traced the frame's primary rays through;
// - owned: a scene of its own over a CameraSpaceScene, refitted or rebuilt at each advance_to from
//   the same interpolated camera-space positions as every backend, on a one-thread device: the
//   peer of the kinetic trees in `kinray bench --structure aabb,boxtree` and their reference in
//   the tests.
// Either way the geometry id is the object index and the primitive id the triangle index, and the
// triangle a ray leaves from is skipped by the occlusion filter that install_filter puts on every
// geometry, so the rule against self-intersection is the one of renderer/shadows/shadow_tracer.h.
#include <embree3/rtcore.h>

#include <atomic>
#include <vector>

#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"

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

/// Occlusion queries through Embree, on a backend's scene (bind) or on a scene of its own.
class EmbreeShadowTracer final : public ShadowTracer {
 public:
  /// How an owned scene follows the motion: refit one dynamic scene, or rebuild it each time.
  enum class Update { kRefit, kRebuild };

  /// Installs the filter that skips a ray's own triangle; call before committing `geometry`.
  static void install_filter(RTCGeometry geometry);

  /// A tracer on the scene an Embree backend hands over with bind.
  EmbreeShadowTracer() = default;
  /// A tracer with a scene of its own over `scene` (which must outlive it), updated at each
  /// advance_to. Builds run on one thread (a device of its own with threads=1).
  EmbreeShadowTracer(const CameraSpaceScene& scene, Update update);
  ~EmbreeShadowTracer() override;
  EmbreeShadowTracer(const EmbreeShadowTracer&) = delete;
  EmbreeShadowTracer& operator=(const EmbreeShadowTracer&) = delete;

  /// The backend hands over the scene it committed for frame time t (it stays valid until the
  /// next bind).
  void bind(RTCScene scene, double t) {
    m_rtc_scene = scene;
    m_time = t;
  }

  [[nodiscard]] std::string name() const override;
  /// Owned: moves the scene to t. Bound: checks that the backend has committed its scene at t
  /// (the backend, not the tracer, moves the geometry); throws std::logic_error otherwise.
  void advance_to(double t) override;
  void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const override;
  void write_stats(nlohmann::json& stats) const override;

 private:
  void update_owned(double t);
  [[nodiscard]] uint64_t trace(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const;

  RTCScene m_rtc_scene = nullptr;
  double m_time = 0;
  mutable std::atomic<uint64_t> m_rays{0}, m_blocked{0};

  // The owned scene (m_scene is null when bound).
  const CameraSpaceScene* m_scene = nullptr;
  bool m_refit = false;
  std::vector<RTCGeometry> m_geometries;
  std::vector<float*> m_vertices;
  std::vector<uint8_t> m_present;
  std::vector<Vec3> m_positions;
  uint64_t m_frames = 0;
  double m_update_s = 0;
};

}  // namespace kinray
