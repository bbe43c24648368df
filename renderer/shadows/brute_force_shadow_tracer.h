#pragma once
// The reference shadow tracer: every triangle present at the frame time is tested against every
// shadow ray in double precision, with the edge-function test of docs/design.md ("The sign rule")
// moved to the ray's origin. Slow (rays x triangles, with one box test per object), exact up to
// double rounding: what the other tracers are tested against, and enough for tiny scenes.
#include <atomic>
#include <vector>

#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"
#include "scenes/present_objects.h"

namespace kinray {

/// How a shadow ray meets one triangle, with the margins `kinray diff` needs to call a
/// disagreement a tie.
struct ShadowCrossing {
  bool pierces = false;  ///< the ray's line meets the triangle (edges included)
  bool hit = false;      ///< ... at 0 < s < s_max
  double s = kInfinity;  ///< where the line meets the triangle's plane (NaN or inf: parallel)
  /// How near the line passes to an edge or vertex: min over edges pq of |E_pq(w)| divided by
  /// the bound on its change when p, q and the origin o are rounded by a relative unit,
  /// |w| (|p| |q - o| + |q| |p - o| + |o| (|p - o| + |q - o|)). 0 = through it.
  double edge_margin = kInfinity;
  double cos = 0;    ///< |cos| of the angle between the ray and the triangle's normal
  double scale = 0;  ///< the largest |vertex|: how far rounding moves the plane, per unit
};

/// The edge-function test of shadow ray `ray` against the triangle (p0, p1, p2): the line
/// o + s w pierces it iff the three E_pq(w) = ((p - o) x (q - o)) . w share a sign (zeros
/// allowed, not all), at s = det(p0 - o, p1 - o, p2 - o) / (E01 + E12 + E20).
[[nodiscard]] ShadowCrossing cross_shadow_ray(const ShadowRay& ray, const Vec3& p0, const Vec3& p1,
                                              const Vec3& p2);

/// Tests every present triangle (`kinray --shadow-tree brute`, and the reference of the tests).
class BruteForceShadowTracer final : public ShadowTracer {
 public:
  /// `scene` must outlive the tracer.
  explicit BruteForceShadowTracer(const CameraSpaceScene& scene);
  [[nodiscard]] std::string name() const override { return "brute"; }
  void advance_to(double t) override;
  void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const override;
  void write_stats(nlohmann::json& stats) const override;

 private:
  [[nodiscard]] bool blocks(const PresentObject& object, const ShadowRay& ray) const;

  const CameraSpaceScene& m_scene;
  double m_time = -kInfinity;
  std::vector<PresentObject> m_present;  ///< at m_time
  mutable std::atomic<uint64_t> m_rays{0}, m_blocked{0}, m_triangle_tests{0};
};

}  // namespace kinray
