// swing: an arm of two rigid links and a hand, hinged at a shoulder and at an elbow, swings like a
// double pendulum over a wall (a floor, the plane y = 0), the hand passing `gap` above it at the
// bottom of each swing (the collision-detection scene of an articulated body brushing past a
// surface). The bound is exact for the keyframed meshes: the hand's depth below the shoulder,
// L1 cos(a) + L2 cos(a + b), is largest when both angles are zero, where the hand's vertices
// are at least `gap` above the floor; every other part stays higher, and linear interpolation
// between keys keeps every vertex above the lower of its two key positions.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"

namespace kinray {

namespace {

constexpr double kUpperArm = 1.0;       // shoulder to elbow
constexpr double kForearm = 0.8;        // elbow to the hand's centre
constexpr double kHand = 0.15;          // the hand's radius
constexpr double kLinkWidth = 0.08;     // the links' half-width (ellipsoids)
constexpr double kLinkLength = 0.42;    // a link's half-length, as a fraction of its length
constexpr double kShoulderSwing = 0.9;  // radians
constexpr double kElbowSwing = 0.6;     // radians, in phase: both zero at the bottom
constexpr double kPeriod = 1.0;         // seconds per swing back and forth

/// `part` (around the origin) appended to `arm`; the part's vertices are arm.positions[first..).
size_t append(Mesh& arm, const Mesh& part) {
  const auto first = uint32_t(arm.positions.size());
  arm.positions.insert(arm.positions.end(), part.positions.begin(), part.positions.end());
  for (const Triangle& t : part.triangles)
    arm.triangles.push_back({t[0] + first, t[1] + first, t[2] + first});
  return first;
}

Mesh ellipsoid(double half_length, int subdivisions) {
  Mesh m = make_sphere(1.0, subdivisions);
  for (Vec3& p : m.positions) p = Vec3(kLinkWidth * p.x(), half_length * p.y(), kLinkWidth * p.z());
  return m;
}

}  // namespace

Scene make_swing(const ProceduralParams& params) {
  Scene scene;
  scene.time_begin = 0;
  scene.time_end = params.duration;
  scene.materials = {Material{"brass", Color(0.85f, 0.66f, 0.30f)},
                     Material{"slate", Color(0.35f, 0.48f, 0.70f)}};
  // half the triangles the floor, half the arm: a third each to its links and its hand
  const int part = cube_subdivisions_for(params.triangles / 6);
  Mesh arm;
  (void)append(arm, ellipsoid(kLinkLength * kUpperArm, part));  // vertices 0 .. fore_begin
  const size_t fore_begin = append(arm, ellipsoid(kLinkLength * kForearm, part));
  const size_t hand_begin = append(arm, make_sphere(kHand, part));
  const double floor_quads = std::max(2.0, params.triangles / 4);
  const int nz = std::max(2, int(std::lround(std::sqrt(floor_quads / 2))));
  const Mesh floor = make_grid(4.4, 2.2, 2 * nz, nz);
  const std::vector<double> times = procedural_key_times(params.duration, params.keyrate);
  const Vec3 shoulder(0, kUpperArm + kForearm + kHand + params.gap.value_or(0), 0);
  scene.objects.push_back(make_keyframed_object(
      "arm", arm, 0, times,
      [&arm, shoulder, fore_begin, hand_begin](double t, std::vector<Vec3>& out) {
        const double phase = std::sin(2 * std::numbers::pi * t / kPeriod);
        const Eigen::AngleAxisd upper(kShoulderSwing * phase, Vec3::UnitZ());
        const Eigen::AngleAxisd fore((kShoulderSwing + kElbowSwing) * phase, Vec3::UnitZ());
        const Vec3 elbow = shoulder + upper * Vec3(0, -kUpperArm, 0);
        const Vec3 hand = elbow + fore * Vec3(0, -kForearm, 0);
        const Vec3 upper_centre = shoulder + upper * Vec3(0, -kUpperArm / 2, 0);
        const Vec3 fore_centre = elbow + fore * Vec3(0, -kForearm / 2, 0);
        for (size_t v = 0; v < out.size(); ++v) {
          const Vec3& p = arm.positions[v];
          if (v >= hand_begin)
            out[v] = hand + fore * p;
          else if (v >= fore_begin)
            out[v] = fore_centre + fore * p;
          else
            out[v] = upper_centre + upper * p;
        }
      }));
  scene.objects.push_back(make_static_object("floor", floor, 1));
  scene.camera.keys = {Camera::look_at(0, Vec3(0, 1.4, -4.6), Vec3(0, 0.9, 0), Vec3::UnitY(), 45)};
  return scene;
}

}  // namespace kinray
