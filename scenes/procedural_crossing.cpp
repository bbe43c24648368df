// crossing: two wobbling spheres travel towards each other, pass through each other and out the
// other side (the collision-detection scene for contacts between two deforming objects). Their
// paths are offset a little so that the surfaces meet off-centre.
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kRadius = 0.6;
constexpr double kTravel = 1.3;   // each centre runs from -+kTravel to +-kTravel along x
constexpr double kOffset = 0.12;  // the centres' offset in y
constexpr double kWobble = 0.06;  // relative amplitude of the surface waves

/// A sphere of unit radius around the origin, centred at `centre` and wobbling with `phase`.
void wobbling_sphere(const Mesh& unit, const Vec3& centre, double t, double phase,
                     std::vector<Vec3>& out) {
  for (size_t v = 0; v < out.size(); ++v) {
    const Vec3& p = unit.positions[v];
    const double r = kRadius * (1 + kWobble * std::sin(4 * p.y() + 3 * p.x() + 5 * t + phase));
    out[v] = centre + r * p;
  }
}

}  // namespace

Scene make_crossing(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"coral", Color(0.92f, 0.45f, 0.38f)},
                     Material{"slate", Color(0.35f, 0.48f, 0.70f)}};
  const Mesh unit = make_sphere(1.0, cube_subdivisions_for(params.triangles / 2));
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  const double duration = params.duration;
  for (int k = 0; k < 2; ++k) {
    const double direction = k == 0 ? 1.0 : -1.0;
    scene.objects.push_back(make_keyframed_object(
        k == 0 ? "left" : "right", unit, uint32_t(k), times,
        [&unit, direction, duration](double t, std::vector<Vec3>& out) {
          const double x = direction * kTravel * (2 * t / duration - 1);
          wobbling_sphere(unit, Vec3(x, direction * kOffset, 0), t, direction > 0 ? 0 : 2, out);
        }));
  }
  scene.camera.keys = {Camera::look_at(0, Vec3(0, 1.2, -4.5), Vec3(0, 0, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
