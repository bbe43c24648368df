// static-moving: most of the image stands still. A ground and a back wall (one key each), a ball
// bouncing and rolling across the ground in front of the wall, and a spinning box that appears a
// third of the way into the shot and disappears at three quarters: objects inserted into and
// deleted from the kinetic structures mid-shot.
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kBallRadius = 0.55;
constexpr double kBounceHeight = 1.1;
constexpr double kBouncePeriod = 1.0;  // seconds between touches of the ground

}  // namespace

Scene make_static_moving(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"slate", Color(0.45f, 0.50f, 0.56f)},
                     Material{"plaster", Color(0.88f, 0.84f, 0.76f)},
                     Material{"tomato", Color(0.90f, 0.30f, 0.24f)},
                     Material{"saffron", Color(0.96f, 0.74f, 0.22f)}};
  const double tris = params.triangles;
  auto grid_cells = [](double budget) {
    return std::max(1, int(std::lround(std::sqrt(budget / 2))));
  };

  const int ground_n = grid_cells(0.25 * tris);
  scene.objects.push_back(make_static_object("ground", make_grid(8, 8, ground_n, ground_n), 0));
  // The wall: a grid stood up (rotated about x so that it faces the camera) at the back.
  const int wall_n = grid_cells(0.15 * tris);
  scene.objects.push_back(make_static_object(
      "wall", make_grid(8, 4, wall_n, wall_n), 1,
      Eigen::Translation3d(0, 2, 3) * Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX())));

  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  const double duration = params.duration;
  const Mesh ball = make_sphere(kBallRadius, cube_subdivisions_for(0.4 * tris));
  scene.objects.push_back(make_rigid_object("ball", ball, 2, times, [duration](double t) {
    // Across the ground and back once per shot; |sin| bounces; rolling without slipping.
    const double x = -2.6 * std::cos(2 * M_PI * t / duration);
    const double y = kBallRadius + kBounceHeight * std::abs(std::sin(M_PI * t / kBouncePeriod));
    const double roll = -(x + 2.6) / kBallRadius;
    return Eigen::Affine3d(Eigen::Translation3d(x, y, 0.4) *
                           Eigen::AngleAxisd(roll, Vec3::UnitZ()));
  }));

  const Mesh box = make_box(Vec3(0.8, 0.8, 0.8), cube_subdivisions_for(0.2 * tris));
  Object spinner = make_rigid_object("appearing box", box, 3, times, [](double t) {
    return Eigen::Affine3d(Eigen::Translation3d(1.4, 0.9, 1.6) *
                           Eigen::AngleAxisd(1.7 * t, Vec3(0.3, 1, 0.2).normalized()));
  });
  spinner.appear = duration / 3;
  spinner.disappear = 0.75 * duration;
  scene.objects.push_back(std::move(spinner));

  scene.camera.keys = {
      Camera::look_at(0, Vec3(0.9, 2.6, -8.0), Vec3(0, 1.0, 0.8), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
