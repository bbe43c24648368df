// cloth-slide: a flat cloth slides along x over the top of a still sphere, which lifts it: where
// it passes over the sphere's cap its vertices lie on the concentric sphere of radius
// (radius + gap), elsewhere on the plane that cap meets (the collision-detection scene of a
// surface gliding over another without touching). Every vertex stays (radius + gap) or more from
// the centre; between vertices, and between keys, the cloth cuts chords up to about L^2 / (8
// radius) inside that (L the longest edge: 0.008 at the default 2,000 triangles, 0.0008 at
// 20,000), so a gap above that never touches and a smaller one lets the sphere's vertices poke
// through here and there.
#include <algorithm>
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kRadius = 0.6;
constexpr double kLength = 4.0;  // the cloth along x (the direction it slides in)
constexpr double kWidth = 2.4;   // the cloth along z
constexpr double kSlide = 0.8;   // the cloth's centre runs from -kSlide to +kSlide along x
constexpr double kCap = 0.8;     // the plane's height, as a fraction of (radius + gap)

}  // namespace

Scene make_cloth_slide(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"linen", Color(0.85f, 0.80f, 0.68f)},
                     Material{"slate", Color(0.35f, 0.48f, 0.70f)}};
  // half the triangles each; the cloth's quads about square
  const double quads = std::max(2.0, params.triangles / 4);
  const int nz = std::max(2, int(std::lround(std::sqrt(quads * kWidth / kLength))));
  const int nx = std::max(2, int(std::lround(quads / nz)));
  const Mesh sheet = make_grid(kLength, kWidth, nx, nz);
  const Mesh ball = make_sphere(kRadius, cube_subdivisions_for(params.triangles / 2));
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  const double duration = params.duration;
  const double draped = kRadius + params.gap.value_or(0);
  scene.objects.push_back(make_keyframed_object(
      "cloth", sheet, 0, times, [&sheet, duration, draped](double t, std::vector<Vec3>& out) {
        const double shift = kSlide * (2 * t / duration - 1);
        for (size_t v = 0; v < out.size(); ++v) {
          const double x = sheet.positions[v].x() + shift, z = sheet.positions[v].z();
          const double d = std::sqrt(x * x + z * z);
          const double y =
              std::max(kCap * draped, std::sqrt(std::max(0.0, draped * draped - d * d)));
          out[v] = Vec3(x, y, z);
        }
      }));
  scene.objects.push_back(make_static_object("sphere", ball, 1));
  scene.camera.keys = {Camera::look_at(0, Vec3(0.8, 2.4, -3.4), Vec3(0, 0, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
