// wavy-sphere: the default scene and the benchmark scene. A unit cube sphere spins slowly about a
// tilted axis while three travelling waves run over its surface (radial displacement
// sum_i a_i sin(k_i (d_i . p) - w_i t), p the rest direction). The camera is fixed, fov 45, at the
// distance where the sphere covers about a third of a square image. At 24 keys/s the surface moves
// on average about 1.6 pixels per key interval at 512 x 512 (measured in
// tests/scenes/test_procedural.cpp and documented in docs/scene_format.md).
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

struct Wave {
  Vec3 direction;        ///< the wave travels along the sphere in the direction of increasing d . p
  double wavenumber;     ///< radians per unit of d . p
  double angular_speed;  ///< radians per second
  double amplitude;      ///< fraction of the radius
};

// Wavelengths of about a quarter to a sixth of the circumference, periods of 1.3 to 2 seconds:
// the slow swell of a liquid drop, not a vibration.
const Wave kWaves[] = {
    {Vec3(0.0, 1.0, 0.0), 7.0, 2 * M_PI * 0.75, 0.060},
    {Vec3(0.8, 0.2, -0.57).normalized(), 9.0, 2 * M_PI * 0.6, 0.045},
    {Vec3(-0.4, 0.35, 0.85).normalized(), 11.0, -2 * M_PI * 0.5, 0.035},
};
const Vec3 kSpinAxis = Vec3(0.25, 1.0, 0.15).normalized();
constexpr double kSpinRate = 0.18;       // radians per second, a turn every 35 s
constexpr double kCameraDistance = 4.0;  // sphere covers about 1/3 of the image at fov 45

}  // namespace

Scene make_wavy_sphere(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"coral", Color(0.92f, 0.46f, 0.36f)}};
  const Mesh mesh = make_sphere(1.0, cube_subdivisions_for(params.triangles));
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  scene.objects.push_back(make_keyframed_object(
      "wavy-sphere", mesh, 0, times, [&mesh](double t, std::vector<Vec3>& out) {
        const Eigen::Matrix3d spin = Eigen::AngleAxisd(kSpinRate * t, kSpinAxis).toRotationMatrix();
        for (size_t v = 0; v < out.size(); ++v) {
          const Vec3& p = mesh.positions[v];
          double height = 1.0;
          for (const Wave& wave : kWaves)
            height += wave.amplitude *
                      std::sin(wave.wavenumber * wave.direction.dot(p) - wave.angular_speed * t);
          out[v] = spin * (height * p);
        }
      }));
  const Vec3 eye = kCameraDistance * Vec3(0.35, 0.45, -1.0).normalized();
  scene.camera.keys = {Camera::look_at(0, eye, Vec3::Zero(), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
