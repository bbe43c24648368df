// cloth: a square sheet hanging from a rod. Each vertical strip of the sheet is an inextensible
// curve whose tangent turns by theta(s) = Theta(u, t) (s / L)^1.5 along its arc length s: the top
// hangs straight and the curvature grows towards the free edge, so the strip curls into a spiral
// (which never crosses itself). Theta swings between about +-250 degrees with a phase that runs
// across the width: the lower part of the cloth rolls up in front of the upper part (towards the
// camera), unrolls, and rolls up behind it, so the depth order of the cloth's own triangles
// changes during the shot without the cloth passing through itself.
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kWidth = 2.0;
constexpr double kLength = 2.0;
constexpr double kTop = 1.0;
constexpr double kMaxTurn = 1.4 * M_PI;  // beyond pi the free edge comes back up over the sheet
constexpr double kCurlExponent = 1.5;
constexpr double kPeriod = 3.0;         // seconds for a roll in front, and back, and behind
constexpr double kPhasePerWidth = 0.8;  // radians of phase across the width: the cloth waves

}  // namespace

Scene make_cloth(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"teal cloth", Color(0.18f, 0.56f, 0.62f)},
                     Material{"brass rod", Color(0.78f, 0.62f, 0.30f)}};
  const int n = std::max(2, int(std::lround(std::sqrt(params.triangles / 2.0))));
  // Grid vertex (i, j): i across the width, j down the arc length.
  const Mesh sheet = make_grid(kWidth, kLength, n, n);
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  scene.objects.push_back(
      make_keyframed_object("cloth", sheet, 0, times, [n](double t, std::vector<Vec3>& out) {
        const size_t row = size_t(n) + 1;
        const double step = kLength / n;
        for (int i = 0; i <= n; ++i) {
          const double u = kWidth * (double(i) / n - 0.5);
          const double turn = kMaxTurn * std::sin(2 * M_PI * t / kPeriod - kPhasePerWidth * u);
          Vec3 p(u, kTop, 0.0);
          out[size_t(i)] = p;
          for (int j = 0; j < n; ++j) {
            // Midpoint rule: the chord of each arc-length step follows the tangent at its middle.
            const double theta = turn * std::pow((j + 0.5) / n, kCurlExponent);
            p += step * Vec3(0.0, -std::cos(theta), -std::sin(theta));
            out[size_t(j + 1) * row + size_t(i)] = p;
          }
        }
      }));
  const Mesh rod = make_box(Vec3(kWidth + 0.3, 0.08, 0.08), 1);
  scene.objects.push_back(
      make_static_object("rod", rod, 1, Eigen::Affine3d(Eigen::Translation3d(0, kTop + 0.045, 0))));
  scene.camera.keys = {
      Camera::look_at(0, Vec3(1.2, 0.7, -4.6), Vec3(0, 0.25, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
