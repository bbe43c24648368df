// flythrough: the geometry stands still and the camera moves. A field of pillars on a ground
// plane, with lintels across the central aisle; the camera weaves down the aisle at 4.5 m/s,
// banking into its turns and zooming in (fov 60 -> 48 -> 60), keyed at `keyrate`. Pillars and
// lintels pass beside and over the camera and the ground runs beneath it, so triangles cross the
// eye plane and end up behind the camera: the case the kinetic row tracking must survive without
// clipping.
#include <cmath>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kSpeed = 4.5;  // metres per second along +z
constexpr double kStartZ = -6.0;
constexpr double kRowSpacing = 4.0;  // pillar rows along z
constexpr double kSway = 1.2;        // metres either side of the aisle's centre line
constexpr double kSwayPeriod = 4.0;  // seconds

Vec3 camera_position(double t) {
  return Vec3(kSway * std::sin(2 * M_PI * t / kSwayPeriod), 1.6 + 0.35 * std::sin(M_PI * t / 2),
              kStartZ + kSpeed * t);
}

}  // namespace

Scene make_flythrough(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"meadow", Color(0.42f, 0.62f, 0.34f)},
                     Material{"limestone", Color(0.86f, 0.82f, 0.72f)},
                     Material{"terracotta", Color(0.80f, 0.45f, 0.32f)}};

  // Rows of pillars from behind the start to well beyond where the camera ends, so that the view
  // ahead is never empty.
  const double z_first = kStartZ - 2.0;
  const double z_last = camera_position(params.duration).z() + 40.0;
  const int rows = int(std::ceil((z_last - z_first) / kRowSpacing));
  const double columns[] = {-6.5, -2.2, 2.2, 6.5};
  const int lintels = rows / 2;  // on every odd row
  const int boxes = rows * 4 + lintels;

  // Three quarters of the triangle budget to the boxes, whatever their subdivision leaves to the
  // ground (at least two triangles), so the total stays close to the request.
  const int subdivisions = std::max(1, int(std::sqrt(0.75 * params.triangles / boxes / 12.0)));
  const double ground_budget =
      std::max(2.0, params.triangles - 12.0 * subdivisions * subdivisions * boxes);
  const double ground_width = 26.0, ground_length = z_last - z_first + 8.0;
  const int ground_nx =
      std::max(1, int(std::lround(std::sqrt(ground_budget / 2 * ground_width / ground_length))));
  const int ground_nz = std::max(1, int(std::lround(ground_budget / 2 / ground_nx)));
  scene.objects.push_back(
      make_static_object("ground", make_grid(ground_width, ground_length, ground_nx, ground_nz), 0,
                         Eigen::Affine3d(Eigen::Translation3d(0, 0, 0.5 * (z_first + z_last)))));

  uint32_t seed = 12345;  // a fixed linear congruential sequence: the same heights on every run
  auto next_uniform = [&seed] {
    seed = seed * 1664525u + 1013904223u;
    return double(seed >> 8) / double(1u << 24);
  };
  for (int r = 0; r < rows; ++r) {
    const double z = z_first + r * kRowSpacing;
    for (double x : columns) {
      const double height = 2.6 + 2.4 * next_uniform();
      scene.objects.push_back(
          make_static_object("pillar", make_box(Vec3(0.8, height, 0.8), subdivisions), 1,
                             Eigen::Affine3d(Eigen::Translation3d(x, 0.5 * height, z))));
    }
    if (r % 2 == 1)
      scene.objects.push_back(
          make_static_object("lintel", make_box(Vec3(5.2, 0.45, 0.9), subdivisions), 2,
                             Eigen::Affine3d(Eigen::Translation3d(0, 3.05, z))));
  }

  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  scene.camera.keys.clear();
  for (double t : times) {
    const double dt = 1e-3;
    const Vec3 eye = camera_position(t);
    const Vec3 forward =
        (camera_position(t + dt) - camera_position(t - dt)).normalized() - Vec3(0, 0.08, 0);
    // Bank into the turn: roll against the sideways acceleration of the sway.
    const double roll = 0.18 * std::sin(2 * M_PI * t / kSwayPeriod);
    const Vec3 up = Eigen::AngleAxisd(roll, forward.normalized()) * Vec3::UnitY();
    const double fov = 60.0 - 12.0 * std::sin(M_PI * t / params.duration);
    scene.camera.keys.push_back(Camera::look_at(t, eye, eye + forward, up, fov));
  }
  return scene;
}

}  // namespace kinray
