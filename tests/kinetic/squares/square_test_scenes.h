#pragma once
// Scenes and checks shared by the per-square sets' tests: a synthetic scene that reaches every
// case, random scenes across the eye plane, random times, and the brute-force comparisons (the
// audit, square_overlap) and the centre-sample check (ray_pierces).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "kinetic/squares/pixel_square_sets.h"
#include "tests/kinetic/grid/grid_test_scenes.h"

namespace kinray::test {

using Vec = Eigen::Vector3d;

/// A triangle given by its image coordinates and depths at each key.
inline OwnedMesh image_triangle(std::vector<double> times,
                                const std::vector<std::array<std::array<double, 3>, 3>>& keys) {
  std::vector<std::array<Vec, 3>> camera;
  for (const auto& key : keys) {
    std::array<Vec, 3> k;
    for (size_t v = 0; v < 3; ++v) k[v] = at_depth(key[v][0], key[v][1], key[v][2]);
    camera.push_back(k);
  }
  return moving_triangle(std::move(times), camera);
}

/// 16x12 (x in [-4/3, 4/3], y in [-1, 1]), three keys over [0, 2].
inline TestScene synthetic_scene() {
  TestScene scene;
  scene.width = 16;
  scene.height = 12;
  const std::vector<double> times = {0.0, 1.0, 2.0};
  // Translating across the image, leaving it on the right.
  scene.meshes.push_back(
      image_triangle(times, {{{{-1.8, 0.2, 3}, {-1.2, 0.8, 3.5}, {-1.5, -0.3, 2.5}}},
                             {{{-0.3, 0.1, 3}, {0.3, 0.7, 3.5}, {0.0, -0.4, 2.5}}},
                             {{{1.2, -0.2, 3}, {1.8, 0.4, 3.5}, {1.5, -0.7, 2.5}}}}));
  // Rotating about (0.2, -0.1) while it moves in depth.
  std::vector<std::array<std::array<double, 3>, 3>> rotating;
  for (int k = 0; k < 3; ++k) {
    std::array<std::array<double, 3>, 3> key;
    for (int v = 0; v < 3; ++v) {
      const double a = 1.3 * k + 2.0944 * v;
      key[size_t(v)] = {0.2 + 0.7 * std::cos(a), -0.1 + 0.6 * std::sin(a), 2.0 + 0.8 * k};
    }
    rotating.push_back(key);
  }
  scene.meshes.push_back(image_triangle(times, rotating));
  // Straddling the eye plane all along (one vertex behind it).
  scene.meshes.push_back(
      moving_triangle(times, {{Vec(-0.5, -0.3, 1.5), Vec(0.6, -0.2, 2.0), Vec(0.1, 0.4, -1.0)},
                              {Vec(-0.2, -0.5, 1.2), Vec(0.7, 0.1, 2.2), Vec(0.4, -0.5, -0.5)},
                              {Vec(0.3, -0.1, 1.8), Vec(-0.6, 0.3, 1.0), Vec(-0.3, 0.2, -2.0)}}));
  // Behind the camera all along.
  scene.meshes.push_back(
      moving_triangle(times, {{Vec(0, 0, -2), Vec(1, 0, -2), Vec(0, 1, -2)},
                              {Vec(-1, 0.5, -1), Vec(0.5, -0.5, -3), Vec(0, 1, -0.5)},
                              {Vec(0.2, 0.2, -0.3), Vec(1, 1, -2), Vec(-1, 0.3, -1)}}));
  // A vertex crossing the eye plane: straddling, then wholly before the eye, then straddling
  // with two vertices behind.
  scene.meshes.push_back(
      moving_triangle(times, {{Vec(0.3, 0.3, 2.0), Vec(-0.4, 0.5, 2.5), Vec(0.0, -0.3, -0.5)},
                              {Vec(0.2, 0.2, 1.5), Vec(-0.5, 0.4, 2.0), Vec(0.1, -0.2, 1.0)},
                              {Vec(0.4, 0.1, -0.8), Vec(-0.3, 0.6, 1.2), Vec(0.5, 0.1, -1.0)}}));
  // Slivers: long and thin across the image diagonally (vertices off-screen, so inside a square
  // there is neither a vertex nor, mostly, a covered corner), and thin along a row.
  scene.meshes.push_back(
      image_triangle(times, {{{{-2.0, -1.3, 2}, {2.0, 1.1, 2}, {2.0, 1.115, 2}}},
                             {{{-2.0, -1.0, 2}, {2.0, 1.3, 2.2}, {2.0, 1.312, 2.2}}},
                             {{{-2.0, -1.5, 2}, {2.0, 0.8, 1.8}, {2.0, 0.81, 1.8}}}}));
  scene.meshes.push_back(
      image_triangle(times, {{{{-2.0, 0.02, 2}, {2.0, 0.05, 2}, {2.0, 0.06, 2}}},
                             {{{-2.0, -0.13, 2}, {2.0, -0.08, 2}, {2.0, -0.07, 2}}},
                             {{{-2.0, 0.35, 2}, {2.0, 0.31, 2}, {2.0, 0.315, 2}}}}));
  // A tiny triangle wandering inside squares, and a short sliver crossing them between corners.
  scene.meshes.push_back(
      image_triangle(times, {{{{-0.61, 0.52, 1}, {-0.60, 0.53, 1}, {-0.605, 0.51, 1}}},
                             {{{0.41, -0.27, 1}, {0.42, -0.26, 1}, {0.415, -0.28, 1}}},
                             {{{0.91, 0.73, 1}, {0.92, 0.74, 1}, {0.915, 0.72, 1}}}}));
  scene.meshes.push_back(
      image_triangle(times, {{{{-0.95, -0.62, 3}, {-0.71, -0.48, 3}, {-0.70, -0.475, 3}}},
                             {{{0.05, -0.62, 3}, {0.29, -0.45, 3}, {0.30, -0.447, 3}}},
                             {{{0.55, 0.12, 3}, {0.81, 0.29, 3}, {0.82, 0.293, 3}}}}));
  // Round coordinates put some edges exactly through corners (ties, all along the still
  // stretches before the first key and after the last): a small deterministic jitter keeps them
  // apart.
  int n = 0;
  for (OwnedMesh& m : scene.meshes)
    for (Vec& p : m.positions) p += 1e-3 * Vec(std::sin(++n * 1.7), std::sin(n * 2.3), 0);
  return scene;
}

/// n random times in [t0, t1], ascending.
inline std::vector<double> random_times(double t0, double t1, int n, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(t0, t1);
  std::vector<double> times(static_cast<size_t>(n));
  for (double& t : times) t = u(rng);
  std::sort(times.begin(), times.end());
  return times;
}

/// Advances through the times, auditing at each; returns the ties met.
inline size_t expect_matches_brute_force(PixelSquareSets& sets, const std::vector<double>& times) {
  size_t ties = 0;
  for (double t : times) {
    sets.advance_to(t);
    const std::vector<std::string> problems = sets.audit(&ties);
    EXPECT_TRUE(problems.empty()) << problems.size() << " problems, first: " << problems.front();
    if (!problems.empty()) break;
  }
  return ties;
}

/// Every triangle whose sign rule clearly holds at a pixel's centre ray is in its square's set.
inline void expect_centre_hits_held(const PixelSquareSets& sets) {
  const GridInput& in = sets.input();
  const PixelRays& rays = in.rays;
  for (uint32_t m = 0; m < in.meshes.size(); ++m) {
    if (!in.meshes[m].present(sets.now())) continue;
    for (uint32_t tri = 0; tri < in.meshes[m].triangles.size(); ++tri) {
      const auto p = sets.triangle_at(m, tri, sets.now());
      for (int j = 0; j < rays.height; ++j)
        for (int i = 0; i < rays.width; ++i) {
          if (ray_pierces(p[0], p[1], p[2], rays.x(i), rays.y(j)) != Overlap::kYes) continue;
          const auto set = sets.triangles(i, j);
          EXPECT_NE(std::find(set.begin(), set.end(), SquareTriangle{m, tri}), set.end())
              << "mesh " << m << " triangle " << tri << " pierces the centre of (" << i << ", " << j
              << ") at t = " << sets.now();
        }
    }
  }
}

/// 24 random triangles on random flightplans over keys 0, 0.7, 1.5, 2, about a third of their
/// vertices behind the eye at any time; `welded`: instead, one mesh of 4 x 5 random vertices
/// joined as a grid of 24 triangles, each vertex shared by up to six of them.
inline TestScene random_scene(unsigned seed, int width, int height, bool welded) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> xy(-2.5, 2.5), z(-1.5, 4.0);
  TestScene scene;
  scene.width = width;
  scene.height = height;
  const std::vector<double> times = {0.0, 0.7, 1.5, 2.0};
  auto random_point = [&] { return Vec(xy(rng), xy(rng), z(rng)); };
  if (!welded) {
    for (int t = 0; t < 24; ++t) {
      std::vector<std::array<Vec, 3>> keys;
      for (size_t k = 0; k < times.size(); ++k)
        keys.push_back({random_point(), random_point(), random_point()});
      scene.meshes.push_back(moving_triangle(times, keys));
    }
    return scene;
  }
  OwnedMesh grid;
  grid.times = times;
  grid.vertex_count = 20;
  for (size_t k = 0; k < times.size(); ++k)
    for (int v = 0; v < 20; ++v) grid.positions.push_back(random_point());
  for (uint32_t r = 0; r < 3; ++r)
    for (uint32_t c = 0; c < 4; ++c) {
      const uint32_t v = r * 5 + c;
      grid.triangles.push_back({v, v + 1, v + 5});
      grid.triangles.push_back({v + 1, v + 6, v + 5});
    }
  scene.meshes.push_back(grid);
  return scene;
}

}  // namespace kinray::test
