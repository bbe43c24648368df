// orbit: rigid bodies around a central sphere. Two spheres and two tumbling boxes orbit on
// inclined circles; seen from the camera each passes in front of and behind the centre and the
// others. The small sphere's orbit breathes between radii 0.9 and 1.9 and the long box's orbit is
// closer than its half-length, so both sink into the central sphere at times (interpenetration:
// depth order changes along lines of intersection, not only at silhouettes).
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

struct Orbiter {
  const char* name;
  bool sphere;       ///< else a box
  Vec3 size;         ///< sphere: x = radius; box: edge lengths
  double budget;     ///< share of the triangle count
  double radius;     ///< orbit radius
  double breathing;  ///< orbit radius varies by +- this, twice per orbit
  Vec3 normal;       ///< orbit plane normal (the sense of the orbit follows the right hand)
  double period;     ///< seconds per orbit
  double phase;      ///< radians at t = 0
  Vec3 tumble_axis;
  double tumble_rate;  ///< radians per second
  Color color;
};

const Orbiter kOrbiters[] = {
    {"moon", true, Vec3(0.42, 0, 0), 0.2, 1.75, 0.0, Vec3(0.25, 1, 0.1), 3.0, 0.3, Vec3::UnitY(),
     0.8, Color(0.36f, 0.58f, 0.90f)},
    {"pebble", true, Vec3(0.3, 0, 0), 0.1, 1.4, 0.5, Vec3(-0.4, 1, 0.5), 2.2, 2.4, Vec3::UnitX(),
     1.5, Color(0.95f, 0.80f, 0.35f)},
    {"cube", false, Vec3(0.55, 0.55, 0.55), 0.12, 2.2, 0.0, Vec3(0.9, 0.5, 0.5), -3.6, 4.0,
     Vec3(1, 1, 0), 2.0, Color(0.55f, 0.80f, 0.45f)},
    {"bar", false, Vec3(1.1, 0.22, 0.22), 0.12, 1.35, 0.0, Vec3(1, 0.15, 0.3), 2.6, 1.0,
     Vec3(0, 0.3, 1), 2.6, Color(0.85f, 0.42f, 0.70f)},
};
constexpr double kCentreRadius = 1.0;
constexpr double kCentreBudget = 0.46;

}  // namespace

Scene make_orbit(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"sandstone", Color(0.90f, 0.55f, 0.38f)}};
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);

  const Mesh centre =
      make_sphere(kCentreRadius, cube_subdivisions_for(kCentreBudget * params.triangles));
  scene.objects.push_back(make_rigid_object("centre", centre, 0, times, [](double t) {
    return Eigen::Affine3d(Eigen::AngleAxisd(0.3 * t, Vec3::UnitY()));
  }));

  for (const Orbiter& orbiter : kOrbiters) {
    scene.materials.push_back(Material{orbiter.name, orbiter.color});
    const int subdivisions = cube_subdivisions_for(orbiter.budget * params.triangles);
    const Mesh mesh = orbiter.sphere ? make_sphere(orbiter.size.x(), subdivisions)
                                     : make_box(orbiter.size, subdivisions);
    // An orthonormal basis (a, b) of the orbit plane.
    const Vec3 normal = orbiter.normal.normalized();
    const Vec3 a = normal.unitOrthogonal();
    const Vec3 b = normal.cross(a);
    const Vec3 tumble_axis = orbiter.tumble_axis.normalized();
    scene.objects.push_back(make_rigid_object(
        orbiter.name, mesh, uint32_t(scene.materials.size() - 1), times, [&](double t) {
          const double angle = orbiter.phase + 2 * M_PI * t / orbiter.period;
          const double radius = orbiter.radius + orbiter.breathing * std::cos(2 * angle);
          const Vec3 centre_of_mass = radius * (std::cos(angle) * a + std::sin(angle) * b);
          return Eigen::Affine3d(Eigen::Translation3d(centre_of_mass) *
                                 Eigen::AngleAxisd(orbiter.tumble_rate * t, tumble_axis));
        }));
  }
  scene.camera.keys = {
      Camera::look_at(0, Vec3(1.5, 2.2, -6.5), Vec3(0, -0.1, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
