// glide: two wobbling spheres travel towards each other on parallel paths and glide past each
// other, their surfaces at least `gap` apart (the collision-detection scene of near misses: the
// bodies come close for much of the shot and touch rarely or never). The bound is exact for the
// keyframed meshes: every vertex, and so every triangle, lies within the largest wobbling radius
// of its centre at every time (linear interpolation between keys keeps it there), and the paths
// are that radius twice plus the gap apart. The bulges rarely line up at the closest points:
// the spheres touch, briefly, from about gap = -0.03.
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kRadius = 0.6;
constexpr double kTravel = 1.0;   // each centre runs from -+kTravel to +-kTravel along x
constexpr double kWobble = 0.05;  // relative amplitude of the surface waves

}  // namespace

Scene make_glide(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"coral", Color(0.92f, 0.45f, 0.38f)},
                     Material{"slate", Color(0.35f, 0.48f, 0.70f)}};
  const Mesh unit = make_sphere(1.0, cube_subdivisions_for(params.triangles / 2));
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  const double duration = params.duration;
  // the paths' distance: the largest radius twice, plus the gap
  const double offset = 2 * kRadius * (1 + kWobble) + params.gap.value_or(0);
  for (int k = 0; k < 2; ++k) {
    const double direction = k == 0 ? 1.0 : -1.0;
    const double phase = k == 0 ? 0 : 2;
    scene.objects.push_back(make_keyframed_object(
        k == 0 ? "lower" : "upper", unit, uint32_t(k), times,
        [&unit, direction, duration, offset, phase](double t, std::vector<Vec3>& out) {
          const Vec3 centre(direction * kTravel * (2 * t / duration - 1), -direction * offset / 2,
                            0);
          for (size_t v = 0; v < out.size(); ++v) {
            const Vec3& p = unit.positions[v];
            const double r =
                kRadius * (1 + kWobble * std::sin(4 * p.y() + 3 * p.x() + 5 * t + phase));
            out[v] = centre + r * p;
          }
        }));
  }
  scene.camera.keys = {Camera::look_at(0, Vec3(0, 0.6, -4.5), Vec3(0, 0, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
