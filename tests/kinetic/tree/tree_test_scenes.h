#pragma once
// Camera-space scenes for the kinetic tree tests: a deforming grid mesh whose vertices move
// randomly between keys, a soup of small tumbling triangles with other key times, a static mesh
// and a mesh that appears and disappears while the trees run.
#include <cmath>
#include <random>
#include <vector>

#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "kinetic/tree/tree_query.h"
#include "tests/kinetic/grid/grid_test_scenes.h"

namespace kinray::test {

/// A (cols x rows) grid of quads in the plane z = depth, each vertex moved by random offsets of
/// size `amplitude` at every key.
inline OwnedMesh deforming_grid(std::mt19937& rng, int cols, int rows, std::vector<double> times,
                                double amplitude, double depth) {
  OwnedMesh m;
  m.times = std::move(times);
  m.vertex_count = size_t((cols + 1) * (rows + 1));
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (size_t k = 0; k < m.times.size(); ++k)
    for (int j = 0; j <= rows; ++j)
      for (int i = 0; i <= cols; ++i)
        m.positions.push_back(
            Vec(-1.0 + 2.0 * i / cols + u(rng), -1.0 + 2.0 * j / rows + u(rng), depth + u(rng)));
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const auto v = uint32_t(j * (cols + 1) + i), w = uint32_t(v + cols + 1);
      m.triangles.push_back({v, v + 1, w});
      m.triangles.push_back({v + 1, w + 1, w});
    }
  return m;
}

/// n separate triangles of size `size` at random places in [-1, 1]^2 x [2, 4], moving randomly.
inline OwnedMesh triangle_soup(std::mt19937& rng, int n, std::vector<double> times, double size) {
  OwnedMesh m;
  m.times = std::move(times);
  m.vertex_count = size_t(3 * n);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec> centres;
  for (int i = 0; i < n; ++i) centres.push_back(Vec(u(rng), u(rng), 3 + u(rng)));
  for (size_t k = 0; k < m.times.size(); ++k)
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        m.positions.push_back(centres[size_t(i)] + 0.3 * Vec(u(rng), u(rng), u(rng)) +
                              size * Vec(u(rng), u(rng), u(rng)));
  for (int i = 0; i < n; ++i)
    m.triangles.push_back({uint32_t(3 * i), uint32_t(3 * i + 1), uint32_t(3 * i + 2)});
  return m;
}

/// Every kind of mesh at once: deforming, tumbling (other keys), static, appearing/disappearing.
inline TestScene mixed_tree_scene(uint32_t seed, int grid = 12) {
  std::mt19937 rng(seed);
  TestScene s;
  s.meshes.push_back(deforming_grid(rng, grid, grid, {0.0, 1.0, 2.0, 3.0}, 0.08, 3.0));
  s.meshes.push_back(triangle_soup(rng, 60, {0.0, 0.7, 1.9, 2.5, 3.0}, 0.15));
  OwnedMesh ground = deforming_grid(rng, 6, 6, {0.0}, 0.0, 5.0);
  ground.is_static = true;
  s.meshes.push_back(ground);
  OwnedMesh visitor = triangle_soup(rng, 20, {0.0, 1.5, 3.0}, 0.2);
  visitor.appear = 0.8;
  visitor.disappear = 2.2;
  s.meshes.push_back(visitor);
  return s;
}

/// A random ray through the scene's region: origin on a sphere around it, aimed at a random point.
inline TreeRay random_tree_ray(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  TreeRay ray;
  ray.origin = Vec(u(rng), u(rng), 3) + 4 * Vec(u(rng), u(rng), u(rng)).normalized();
  ray.direction = Vec(u(rng), u(rng), 3 + u(rng)) - ray.origin;
  if (rng() % 3 == 0) ray.direction *= 0.3;  // a segment that may stop short of the triangles
  ray.s_max = rng() % 2 == 0 ? 1.0 : kInfinityTime;
  return ray;
}

/// An audited kinetic AABB tree, an audited kinetic BoxTree and the bottom-up tree of `scene`
/// (a mixed_tree_scene), advanced together over its shot at random steps of up to `max_step`;
/// check(tree, frame) is called on each of the three at every step.
template <class Check>
void for_each_tree_at_random_times(const TestScene& scene, std::mt19937& rng, double max_step,
                                   Check&& check) {
  KineticBvh aabb(scene.input().meshes, 0, KineticBvh::Config{TreeShape::aabb, true});
  KineticBvh box(scene.input().meshes, 0, KineticBvh::Config{TreeShape::boxtree, true});
  BottomUpBvh bottom_up(scene.input().meshes, 0);
  std::uniform_real_distribution<double> dt(0, max_step);
  for (double t = 0; t < 3.4; t += dt(rng)) {
    aabb.advance_to(t);
    box.advance_to(t);
    bottom_up.update(t);
    const TreeFrame frame(aabb.meshes(), t);
    check(aabb, frame);
    check(box, frame);
    check(bottom_up, frame);
  }
}

}  // namespace kinray::test
