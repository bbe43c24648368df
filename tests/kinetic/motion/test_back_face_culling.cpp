// The proof that back-face culling is sound (kinetic/motion/back_face_culling.h): the cubic sign
// test, meshes it must decline (a solid that turns inside out between two good keys, a torus) and
// one it must accept although its two components pass through each other, culled and still exact
// against the brute-force reference with the audit on.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "kinetic/grid/frustum_grid.h"
#include "kinetic/grid/grid_scene.h"
#include "kinetic/motion/back_face_culling.h"
#include "tests/kinetic/grid/grid_test_scenes.h"

namespace kinray {
namespace {

using test::OwnedMesh;
using test::TestScene;
using test::Vec;

TEST(CubicSign, ProvedByBernsteinCoefficientsOrBySubdivision) {
  EXPECT_EQ(cubic_sign_on_unit_interval({1, 2, 0.5, 3}, 0, 0), 1);
  EXPECT_EQ(cubic_sign_on_unit_interval({-1, -2, -0.5, -3}, 0, 0), -1);
  // (1 - u)^3 - 0.3 (1 - u)^2 u - 0.3 (1 - u) u^2 + u^3 > 0 (0.175 at u = 1/2), but not
  // coefficient by coefficient.
  const std::array<double, 4> dip = {1, -0.1, -0.1, 1};
  EXPECT_EQ(cubic_sign_on_unit_interval(dip, 0, 0), 0);
  EXPECT_EQ(cubic_sign_on_unit_interval(dip, 0, 4), 1);
  // (1 - 2u)^2 touches 0 at u = 1/2: never proved, however deep, with a margin (without one,
  // rounding leaves f(1/2) a hair above 0, which is why the margin is there).
  EXPECT_EQ(cubic_sign_on_unit_interval({1, -1.0 / 3, -1.0 / 3, 1}, 1e-12, 10), 0);
  EXPECT_EQ(cubic_sign_on_unit_interval({1, 1, 1, -1}, 0, 10), 0);  // changes sign
  EXPECT_EQ(cubic_sign_on_unit_interval({1, 1, 1, 1}, 1, 0), 0);    // within the margin
}

// A regular octahedron (radius 1, outward winding) under the linear map `maps[k]` about `centre`
// at key k (times 0, 1, ...).
OwnedMesh mapped_octahedron(const Vec& centre, const std::vector<Eigen::Matrix3d>& maps) {
  const Vec axes[6] = {Vec::UnitX(), -Vec::UnitX(), Vec::UnitY(), -Vec::UnitY(), Vec::UnitZ(), -Vec::UnitZ()};
  OwnedMesh m;
  m.vertex_count = 6;
  m.times.clear();
  for (size_t k = 0; k < maps.size(); ++k) {
    m.times.push_back(double(k));
    for (const Vec& a : axes) m.positions.push_back(centre + maps[k] * a);
  }
  for (uint32_t sx : {0u, 1u})
    for (uint32_t sy : {2u, 3u})
      for (uint32_t sz : {4u, 5u}) {
        const bool flip = ((sx & 1) ^ (sy & 1) ^ (sz & 1)) != 0;
        m.triangles.push_back(flip ? std::array<uint32_t, 3>{sx, sz, sy} : std::array<uint32_t, 3>{sx, sy, sz});
      }
  m.is_static = maps.size() == 1;
  return m;
}

double signed_volume(const OwnedMesh& m, size_t key) {
  double v = 0;
  const auto p = [&](uint32_t i) { return m.positions[key * m.vertex_count + i]; };
  for (const auto& t : m.triangles) v += p(t[0]).dot(p(t[1]).cross(p(t[2])));
  return v;
}

FrustumGridConfig audited() {
  FrustumGridConfig config;
  config.threads = 2;
  config.bands = 2;
  config.audit = true;
  return config;
}

// Both keys are a good octahedron of positive volume (diag(-2, -0.5, 1) has determinant 1), but
// on the chords between them x collapses at t = 1/3 and y at t = 2/3: in between the surface has
// passed through itself and is inside out, and its faces turned to the eye are the back ones. A
// check at the keys alone (volume, closedness, the eye outside) cannot see it; the cubic can.
TEST(BackFaceCulling, DeclinesASolidThatTurnsInsideOutBetweenKeys) {
  TestScene scene;
  const Eigen::Matrix3d turned = Eigen::Vector3d(-2, -0.5, 1).asDiagonal();
  scene.meshes.push_back(mapped_octahedron(Vec(0.2, 0.1, 5), {Eigen::Matrix3d::Identity(), turned}));
  EXPECT_GT(signed_volume(scene.meshes[0], 0), 0);
  EXPECT_GT(signed_volume(scene.meshes[0], 1), 0);
  const GridInput in = scene.input();
  EXPECT_EQ(back_face_cull_sign(in.meshes[0]), 0);

  TestScene still;  // either key alone is culled
  still.meshes.push_back(mapped_octahedron(Vec(0.2, 0.1, 5), {turned}));
  EXPECT_EQ(back_face_cull_sign(still.input().meshes[0]), -1);

  FrustumGrid grid(in, 0.0, audited());
  for (int k = 0; k <= 12; ++k) {
    grid.advance_to(k / 12.0);
    EXPECT_EQ(test::compare_with_brute_force(grid, in).real, 0u) << "t = " << k / 12.0;
  }
  EXPECT_EQ(grid.stats().meshes_culling, 0u);
}

// A closed, consistently oriented torus is not star-shaped: seen from its centre the inner faces
// turn one way and the outer ones the other. The test is sufficient, not necessary: declined.
TEST(BackFaceCulling, DeclinesATorus) {
  constexpr int kAround = 24, kTube = 10;
  OwnedMesh torus;
  torus.is_static = true;
  torus.vertex_count = kAround * kTube;
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(1.0, Vec::UnitX()).toRotationMatrix();
  for (int i = 0; i < kAround; ++i)
    for (int j = 0; j < kTube; ++j) {
      const double u = 2 * std::numbers::pi * i / kAround, v = 2 * std::numbers::pi * j / kTube;
      const Vec p((1 + 0.35 * std::cos(v)) * std::cos(u), (1 + 0.35 * std::cos(v)) * std::sin(u), 0.35 * std::sin(v));
      torus.positions.push_back(Vec(0, 0, 5) + tilt * p);
    }
  const auto id = [&](int i, int j) { return uint32_t(((i + kAround) % kAround) * kTube + (j + kTube) % kTube); };
  for (int i = 0; i < kAround; ++i)
    for (int j = 0; j < kTube; ++j) {
      torus.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      torus.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  TestScene scene;
  scene.meshes.push_back(torus);
  EXPECT_EQ(back_face_cull_sign(scene.input().meshes[0]), 0);
}

// A cube as a loader gives it: every face with its own four vertices (split along the normal
// seams). Welding the copies that share a position at every key closes it: culled. When the
// copies of one corner part at a key, the cube has a crack there: declined.
TEST(BackFaceCulling, WeldsVerticesThatMoveTogether) {
  OwnedMesh cube;
  cube.times = {0.0, 1.0};
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(0.8, Vec(0.2, 1, 0.3).normalized()).toRotationMatrix();
  for (int k = 0; k < 2; ++k)
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {1.0, -1.0}) {
        const Vec n = sign * Vec::Unit(axis), u = Vec::Unit((axis + 1) % 3), v = n.cross(u);
        for (const Vec& corner : {Vec(n - u - v), Vec(n + u - v), Vec(n + u + v), Vec(n - u + v)})
          cube.positions.push_back(Vec(0.3, -0.2, 6) + (k == 0 ? corner : Vec(turn * corner)));
      }
  cube.vertex_count = 24;
  for (uint32_t f = 0; f < 6; ++f) {
    cube.triangles.push_back({4 * f, 4 * f + 1, 4 * f + 2});
    cube.triangles.push_back({4 * f, 4 * f + 2, 4 * f + 3});
  }
  TestScene scene;
  scene.meshes.push_back(cube);
  EXPECT_EQ(back_face_cull_sign(scene.input().meshes[0]), -1);
  scene.meshes[0].positions[24] += Vec(0, 0, 1e-9);  // one copy of a corner parts at key 1
  EXPECT_EQ(back_face_cull_sign(scene.input().meshes[0]), 0);
}

// One mesh of two tumbling octahedra that pass through each other between keys: each component
// is star-shaped around its own centroid, the eye is outside both, so the first hit is still a
// face turned to the eye. Culled, and every frame equals the brute-force reference.
TEST(BackFaceCulling, AcceptsComponentsThatPassThroughEachOther) {
  constexpr int kKeys = 5;
  std::vector<Eigen::Matrix3d> spin_a, spin_b;
  for (int k = 0; k < kKeys; ++k) {
    spin_a.push_back(0.9 * Eigen::AngleAxisd(0.6 * k, Vec(0.3, 1, 0.2).normalized()).toRotationMatrix());
    spin_b.push_back(0.7 * Eigen::AngleAxisd(-0.5 * k, Vec(1, 0.2, 0.4).normalized()).toRotationMatrix());
  }
  OwnedMesh a = mapped_octahedron(Vec::Zero(), spin_a), b = mapped_octahedron(Vec::Zero(), spin_b);
  OwnedMesh both;
  both.times = a.times;
  both.vertex_count = 12;
  for (int k = 0; k < kKeys; ++k) {
    const double s = double(k) / (kKeys - 1);
    for (int v = 0; v < 6; ++v) both.positions.push_back(Vec(-0.8 + 1.6 * s, 0, 3) + a.positions[size_t(k * 6 + v)]);
    for (int v = 0; v < 6; ++v) both.positions.push_back(Vec(0.8 - 1.6 * s, 0.3, 3.2) + b.positions[size_t(k * 6 + v)]);
  }
  both.triangles = a.triangles;
  for (auto t : b.triangles) both.triangles.push_back({t[0] + 6, t[1] + 6, t[2] + 6});
  TestScene scene;
  scene.meshes.push_back(both);
  const GridInput in = scene.input();
  EXPECT_EQ(back_face_cull_sign(in.meshes[0]), -1);

  FrustumGrid grid(in, 0.0, audited());
  size_t covered = 0;
  for (int k = 0; k <= 40; ++k) {
    grid.advance_to(4.0 * k / 40);
    const test::Comparison c = test::compare_with_brute_force(grid, in);
    EXPECT_EQ(c.real, 0u) << "t = " << 4.0 * k / 40;
    covered += c.covered;
  }
  EXPECT_GT(covered, 4000u);
  EXPECT_EQ(grid.stats().meshes_culling, 1u);
  EXPECT_GT(grid.stats().triangles_culled, 0u);
}

}  // namespace
}  // namespace kinray
