// cloth-fold: a rippled square sheet lying flat whose right half folds over about the middle
// line, through 200 degrees: it comes down onto the left half and passes through it, so the
// cloth collides with itself (the collision-detection scene for self-contacts). The ripple is
// even across the fold line, so the folded half meets the other along curves, first here and
// there and then everywhere, rather than all at once.
#include <algorithm>
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kSize = 2.0;
constexpr double kRipple = 0.04;                   // amplitude of the rest shape's ripple
constexpr double kFoldAngle = 200.0 * M_PI / 180;  // past flat, so the halves pass through

}  // namespace

Scene make_cloth_fold(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"linen", Color(0.85f, 0.80f, 0.68f)}};
  // an even number of quads across, so that a column of vertices lies on the fold line x = 0
  const int n = std::max(2, 2 * int(std::lround(std::sqrt(params.triangles / 2.0) / 2)));
  const Mesh sheet = make_grid(kSize, kSize, n, n);
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  const double duration = params.duration;
  scene.objects.push_back(make_keyframed_object(
      "cloth", sheet, 0, times, [&sheet, duration](double t, std::vector<Vec3>& out) {
        const double s = std::clamp(t / duration, 0.0, 1.0);
        const double angle = kFoldAngle * s * s * (3 - 2 * s);  // smoothstep: rests at both ends
        const double c = std::cos(angle), sn = std::sin(angle);
        for (size_t v = 0; v < out.size(); ++v) {
          const Vec3& rest = sheet.positions[v];
          const double y =
              kRipple * std::cos(3 * M_PI * rest.x()) * std::sin(3 * M_PI * rest.z() + 0.5);
          out[v] = rest.x() > 0 ? Vec3(rest.x() * c - y * sn, rest.x() * sn + y * c, rest.z())
                                : Vec3(rest.x(), y, rest.z());
        }
      }));
  scene.camera.keys = {
      Camera::look_at(0, Vec3(0.6, 2.6, -2.6), Vec3(0, 0.2, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
