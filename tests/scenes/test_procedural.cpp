// The built-in procedural scenes: sizes, motion, and the visibility events each exists to provoke,
// measured with a brute-force rasterizer over the same camera-space flightplans the backends use.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <map>

#include "scenes/camera_space.h"
#include "scenes/mesh_builders.h"
#include "scenes/procedural.h"
#include "util/input_error.h"

namespace kinray {
namespace {

constexpr uint32_t kNoPrim = std::numeric_limits<uint32_t>::max();

/// Calls hit(object, prim, pixel, depth) for every pixel-centre ray of `image` that pierces a
/// visible triangle at time t (the sign rule of docs/design.md; depth = camera-space z of the hit).
void rasterize(const CameraSpaceScene& scene, const PixelRays& image, double t,
               const std::function<void(uint32_t, uint32_t, size_t, double)>& hit) {
  std::vector<Vec3> p;
  const double aspect = double(image.width) / image.height;
  for (const CameraSpaceObject& object : scene.objects) {
    if (!object.visible(t)) continue;
    object.positions_at(t, p);
    const std::vector<Triangle>& triangles = scene.triangles(object.object);
    for (uint32_t f = 0; f < triangles.size(); ++f) {
      const Vec3 &v0 = p[triangles[f][0]], &v1 = p[triangles[f][1]], &v2 = p[triangles[f][2]];
      const double orientation = v0.dot(v1.cross(v2));
      if (orientation == 0) continue;
      int i0 = 0, i1 = image.width - 1, j0 = 0, j1 = image.height - 1;
      if (v0.z() > 0 && v1.z() > 0 && v2.z() > 0) {  // else test every pixel
        double x_min = kInfinity, x_max = -kInfinity, y_min = kInfinity, y_max = -kInfinity;
        for (const Vec3* v : {&v0, &v1, &v2}) {
          x_min = std::min(x_min, v->x() / v->z());
          x_max = std::max(x_max, v->x() / v->z());
          y_min = std::min(y_min, v->y() / v->z());
          y_max = std::max(y_max, v->y() / v->z());
        }
        i0 = std::max(i0, int(std::floor(((x_min / aspect + 1) * image.width - 1) / 2)));
        i1 = std::min(i1, int(std::ceil(((x_max / aspect + 1) * image.width - 1) / 2)));
        j0 = std::max(j0, int(std::floor(((1 - y_max) * image.height - 1) / 2)));
        j1 = std::min(j1, int(std::ceil(((1 - y_min) * image.height - 1) / 2)));
      }
      const Vec3 e01 = v0.cross(v1), e12 = v1.cross(v2), e20 = v2.cross(v0);
      const Vec3 normal = (v1 - v0).cross(v2 - v0);
      for (int j = j0; j <= j1; ++j)
        for (int i = i0; i <= i1; ++i) {
          const Vec3 d = image.direction(i, j);
          const double a = e01.dot(d), b = e12.dot(d), c = e20.dot(d);
          const bool inside =
              orientation > 0 ? (a >= 0 && b >= 0 && c >= 0) : (a <= 0 && b <= 0 && c <= 0);
          if (inside)
            hit(object.object, f, size_t(j) * image.width + i, orientation / normal.dot(d));
        }
    }
  }
}

/// Squared-free orientation check: (signed volume, every directed edge used once and its
/// reverse once) of a closed mesh.
struct ClosedMeshReport {
  double volume = 0;
  bool watertight = true;
};
ClosedMeshReport check_closed(const Mesh& mesh) {
  ClosedMeshReport report;
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const Triangle& t : mesh.triangles) {
    report.volume += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]])) / 6;
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed)
    if (count != 1 || directed.count({edge.second, edge.first}) != 1) report.watertight = false;
  return report;
}

TEST(ProceduralMesh, SphereIsClosedOutwardAndRound) {
  for (int n : {1, 3, 10}) {
    const Mesh sphere = make_sphere(2.0, n);
    EXPECT_EQ(sphere.triangles.size(), size_t(12 * n * n));
    EXPECT_EQ(sphere.positions.size(), size_t(6 * n * n + 2));  // Euler: V = F / 2 + 2
    for (const Vec3& p : sphere.positions) EXPECT_NEAR(p.norm(), 2.0, 1e-12);
    const ClosedMeshReport report = check_closed(sphere);
    EXPECT_TRUE(report.watertight);
    EXPECT_GT(report.volume, 0);  // counter-clockwise seen from outside
  }
  EXPECT_NEAR(check_closed(make_sphere(1.0, 30)).volume, 4 * M_PI / 3, 0.01);
}

TEST(ProceduralMesh, BoxAndGrid) {
  const Mesh box = make_box(Vec3(1, 2, 3), 2);
  EXPECT_EQ(box.triangles.size(), 48u);
  const ClosedMeshReport report = check_closed(box);
  EXPECT_TRUE(report.watertight);
  EXPECT_NEAR(report.volume, 6.0, 1e-12);

  const Mesh grid = make_grid(4, 2, 4, 3);
  EXPECT_EQ(grid.triangles.size(), 24u);
  EXPECT_EQ(grid.positions.size(), 20u);
  EXPECT_EQ(grid.uvs.size(), 20u);
  for (const Triangle& t : grid.triangles) {
    const Vec3 normal = (grid.positions[t[1]] - grid.positions[t[0]])
                            .cross(grid.positions[t[2]] - grid.positions[t[0]]);
    EXPECT_GT(normal.y(), 0);  // faces +y
  }
  EXPECT_EQ(grid.positions.front(), Vec3(-2, 0, -1));
  EXPECT_EQ(grid.positions.back(), Vec3(2, 0, 1));
  EXPECT_EQ(cube_subdivisions_for(40000), 58);
  EXPECT_EQ(cube_subdivisions_for(1), 1);
}

bool anything_moves(const Scene& scene) {
  if (scene.camera.keys.size() > 1) return true;
  for (const Object& object : scene.objects)
    if (!object.is_static()) return true;
  return false;
}

TEST(Procedural, EveryBuiltinHasTheRequestedSizeDurationAndKeys) {
  ASSERT_EQ(builtin_scene_names().front(), "wavy-sphere");
  for (const BuiltinScene& builtin : builtin_scenes()) {
    SCOPED_TRACE(builtin.name);
    for (double request : {3000.0, 12000.0}) {
      const Scene scene =
          make_builtin_scene(builtin.name, {{"triangles", request}, {"duration", 1.5}});
      EXPECT_EQ(scene.name, builtin.name);
      EXPECT_NO_THROW(scene.validate(builtin.name));
      EXPECT_NEAR(double(scene.triangle_count()), request, 0.15 * request);
      EXPECT_EQ(scene.time_begin, 0.0);
      EXPECT_EQ(scene.time_end, 1.5);
      EXPECT_TRUE(anything_moves(scene));
      // Keyed at 24 keys per second: 36 intervals over 1.5 s, whether the objects or the camera
      // move.
      EXPECT_EQ(scene.key_times().size(), 37u);
    }
    const Scene defaults = make_builtin_scene(builtin.name);
    EXPECT_EQ(defaults.time_end, builtin.defaults.duration);
    EXPECT_NEAR(double(defaults.triangle_count()), builtin.defaults.triangles,
                0.15 * builtin.defaults.triangles);
    const Scene slow =
        make_builtin_scene(builtin.name, {{"triangles", 500}, {"duration", 2}, {"keyrate", 5}});
    EXPECT_EQ(slow.key_times().size(), 11u);
  }
}

TEST(Procedural, VerticesMoveBetweenKeys) {
  for (const char* name : {"wavy-sphere", "cloth", "orbit", "static-moving"}) {
    SCOPED_TRACE(name);
    const Scene scene = make_builtin_scene(name, {{"triangles", 2000}});
    double motion = 0;
    for (const Object& object : scene.objects)
      for (size_t k = 1; k < object.key_count(); ++k)
        for (size_t v = 0; v < object.vertex_count(); ++v)
          motion = std::max(motion,
                            (object.key_positions[k][v] - object.key_positions[k - 1][v]).norm());
    EXPECT_GT(motion, 1e-3);
  }
}

TEST(Procedural, IsDeterministic) {
  for (const std::string& name : builtin_scene_names()) {
    const Scene a = make_builtin_scene(name, {{"triangles", 1000}});
    const Scene b = make_builtin_scene(name, {{"triangles", 1000}});
    ASSERT_EQ(a.objects.size(), b.objects.size());
    for (size_t o = 0; o < a.objects.size(); ++o) {
      EXPECT_EQ(a.objects[o].key_positions, b.objects[o].key_positions) << name;
      EXPECT_EQ(a.objects[o].triangles, b.objects[o].triangles) << name;
    }
  }
}

TEST(Procedural, BadNamesAndParametersAreInputErrors) {
  auto message = [](const std::string& name, const std::map<std::string, double>& params) {
    try {
      (void)make_builtin_scene(name, params);
    } catch (const InputError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("wavy-spere", {}).find("wavy-sphere, cloth, orbit, flythrough, static-moving"),
            std::string::npos);
  EXPECT_NE(message("cloth", {{"triangle", 10}}).find("triangles, duration, keyrate"),
            std::string::npos);
  for (double bad : {0.0, -5.0, std::numeric_limits<double>::quiet_NaN(), kInfinity})
    for (const char* key : {"triangles", "duration", "keyrate"})
      EXPECT_NE(message("orbit", {{key, bad}}).find(key), std::string::npos) << key << "=" << bad;
  EXPECT_NE(message("orbit", {{"triangles", 1e12}}).find("at most"), std::string::npos);
}

TEST(Procedural, WavySphereScalesFromAHundredToAMillionTriangles) {
  const Scene tiny = make_builtin_scene("wavy-sphere", {{"triangles", 100}});
  EXPECT_NEAR(double(tiny.triangle_count()), 100, 10);
  // A million triangles over a few keys (the full 2 s, 49 keys take ~0.6 GB: see the docs).
  const Scene big = make_builtin_scene("wavy-sphere", {{"triangles", 1e6}, {"duration", 0.125}});
  EXPECT_NEAR(double(big.triangle_count()), 1e6, 0.01e6);
  EXPECT_EQ(big.objects[0].key_count(), 4u);
}

/// The wavy sphere's two figures: the fraction of a 512 x 512 image it covers, and the average
/// distance in pixels that the visible surface moves per key interval.
TEST(Procedural, WavySphereFillsAThirdOfTheImageAndMovesAboutAPixelPerKey) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 6000}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const PixelRays image{512, 512};
  const CameraSpaceObject& sphere = cs.objects[0];
  const std::vector<Triangle>& triangles = scene.objects[0].triangles;
  ASSERT_EQ(sphere.key_times.size(), 49u);

  double coverage_sum = 0, motion_sum = 0, vertex_motion_sum = 0;
  size_t motion_samples = 0, vertex_samples = 0;
  for (size_t k = 0; k + 1 < sphere.key_times.size(); ++k) {
    // Front-most hit per pixel at key k.
    std::vector<double> depth(image.pixel_count(), kInfinity);
    std::vector<uint32_t> prim(image.pixel_count(), kNoPrim);
    rasterize(cs, image, sphere.key_times[k], [&](uint32_t, uint32_t f, size_t pixel, double z) {
      if (z > 0 && z < depth[pixel]) {
        depth[pixel] = z;
        prim[pixel] = f;
      }
    });
    const std::span<const Vec3> now = sphere.key(k), next = sphere.key(k + 1);
    size_t covered = 0;
    for (size_t pixel = 0; pixel < prim.size(); ++pixel) {
      if (prim[pixel] == kNoPrim) continue;
      ++covered;
      // The surface point seen at this pixel, as barycentrics of its triangle, carried to the next
      // key.
      const Triangle& tri = triangles[prim[pixel]];
      const Vec3 d = image.direction(int(pixel % 512), int(pixel / 512)) * depth[pixel];
      Eigen::Matrix3d basis;
      basis << now[tri[0]], now[tri[1]], now[tri[2]];
      const Vec3 weights = basis.inverse() * d;
      const Vec3 moved =
          weights[0] * next[tri[0]] + weights[1] * next[tri[1]] + weights[2] * next[tri[2]];
      const Eigen::Vector2d from(d.x() / d.z(), d.y() / d.z()),
          to(moved.x() / moved.z(), moved.y() / moved.z());
      motion_sum += (to - from).norm() * 256;  // 2 units of the image plane span 512 pixels
      ++motion_samples;
    }
    coverage_sum += double(covered) / double(image.pixel_count());
    // The brief's figure: every vertex on the camera's side of the sphere, projected at keys k and
    // k+1.
    for (size_t v = 0; v < sphere.vertex_count; ++v) {
      if (scene.objects[0].key_positions[k][v].dot(scene.camera.keys[0].position) <= 0) continue;
      const Eigen::Vector2d from = now[v].head<2>() / now[v].z(),
                            to = next[v].head<2>() / next[v].z();
      vertex_motion_sum += (to - from).norm() * 256;
      ++vertex_samples;
    }
  }
  const double intervals = double(sphere.key_times.size() - 1);
  const double coverage = coverage_sum / intervals;
  const double surface_motion = motion_sum / double(motion_samples);
  const double vertex_motion = vertex_motion_sum / double(vertex_samples);
  std::printf(
      "wavy-sphere at 512x512: coverage %.3f, visible surface moves %.2f px per key, "
      "camera-side vertices %.2f px per key\n",
      coverage, surface_motion, vertex_motion);
  EXPECT_NEAR(coverage, 1.0 / 3.0, 0.04);
  EXPECT_GE(surface_motion, 1.0);
  EXPECT_LE(surface_motion, 2.0);
  EXPECT_GE(vertex_motion, 1.0);
  EXPECT_LE(vertex_motion, 2.0);
}

/// Per pixel of a coarse image, over the keys of the shot: whether part A was ever seen in front of
/// part B (both on the pixel's ray, A nearer), and whether B was ever in front of A.
struct DepthSwaps {
  size_t a_in_front = 0, b_in_front = 0, both = 0;  ///< pixel counts
};
DepthSwaps depth_swaps(const Scene& scene, const PixelRays& image,
                       const std::function<int(uint32_t object, uint32_t prim)>& part) {
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  std::vector<uint8_t> seen(image.pixel_count(), 0);  // bit 0: A in front, bit 1: B in front
  for (double t : scene.key_times()) {
    std::vector<double> nearest_a(image.pixel_count(), kInfinity),
        nearest_b(image.pixel_count(), kInfinity);
    rasterize(cs, image, t, [&](uint32_t object, uint32_t prim, size_t pixel, double z) {
      if (z <= 0) return;
      const int which = part(object, prim);
      if (which == 0) nearest_a[pixel] = std::min(nearest_a[pixel], z);
      if (which == 1) nearest_b[pixel] = std::min(nearest_b[pixel], z);
    });
    for (size_t pixel = 0; pixel < seen.size(); ++pixel) {
      if (nearest_a[pixel] == kInfinity || nearest_b[pixel] == kInfinity) continue;
      seen[pixel] |= nearest_a[pixel] < nearest_b[pixel] ? 1 : 2;
    }
  }
  DepthSwaps swaps;
  for (uint8_t s : seen) {
    swaps.a_in_front += (s & 1) != 0;
    swaps.b_in_front += (s & 2) != 0;
    swaps.both += s == 3;
  }
  return swaps;
}

TEST(Procedural, ClothFoldsOverItselfAndSwapsDepthOrder) {
  const Scene scene = make_builtin_scene("cloth", {{"triangles", 2000}});
  const Object& cloth = scene.objects[0];
  ASSERT_EQ(cloth.name, "cloth");
  const uint32_t n = uint32_t(std::lround(std::sqrt(double(cloth.vertex_count())))) - 1;
  ASSERT_EQ(size_t(n + 1) * (n + 1), cloth.vertex_count());
  // Part A: the upper half of the sheet (grid rows run down its length); part B: its lowest third.
  const DepthSwaps swaps =
      depth_swaps(scene, PixelRays{96, 96}, [&](uint32_t object, uint32_t prim) {
        if (object != 0) return -1;
        const double down = double(prim / 2 / n) / n;
        return down < 0.5 ? 0 : down > 2.0 / 3.0 ? 1 : -1;
      });
  std::printf(
      "cloth at 96x96: upper part in front of lower at %zu pixels, lower in front of upper at %zu, "
      "both (a swap) at %zu\n",
      swaps.a_in_front, swaps.b_in_front, swaps.both);
  EXPECT_GT(swaps.a_in_front, 20u);
  EXPECT_GT(swaps.b_in_front, 20u);
  EXPECT_GT(swaps.both, 10u);  // the same pixel sees the order reverse during the shot
}

TEST(Procedural, OrbitersPassInFrontOfEachOtherAndInterpenetrate) {
  const Scene scene = make_builtin_scene("orbit", {{"triangles", 3000}});
  ASSERT_EQ(scene.objects[0].name, "centre");
  // Every orbiter is seen both in front of and behind the central sphere.
  for (uint32_t o = 1; o < scene.objects.size(); ++o) {
    SCOPED_TRACE(scene.objects[o].name);
    const DepthSwaps swaps =
        depth_swaps(scene, PixelRays{64, 64}, [o](uint32_t object, uint32_t) {
          return object == o ? 0 : object == 0 ? 1 : -1;
        });
    EXPECT_GT(swaps.a_in_front, 0u);
    EXPECT_GT(swaps.b_in_front, 0u);
  }
  // Some orbiters have vertices inside the central sphere at some keys (they pass through it).
  std::vector<std::string> penetrating;
  for (size_t o = 1; o < scene.objects.size(); ++o) {
    const Object& object = scene.objects[o];
    bool inside = false;
    for (const auto& key : object.key_positions)
      for (const Vec3& p : key)
        inside |= p.norm() < 0.97;  // the centre's tessellated radius >= 0.97
    if (inside) penetrating.push_back(object.name);
  }
  EXPECT_EQ(penetrating, (std::vector<std::string>{"pebble", "bar"}));
}

TEST(Procedural, FlythroughCrossesTheEyePlane) {
  const Scene scene = make_builtin_scene("flythrough", {{"triangles", 3000}});
  ASSERT_GT(scene.camera.keys.size(), 24u);
  const CameraKey& first = scene.camera.keys.front();
  const CameraKey& middle = scene.camera.keys[scene.camera.keys.size() / 2];
  EXPECT_GT((middle.position - first.position).norm(), 5.0);
  EXPECT_GT(first.orientation.angularDistance(middle.orientation), 0.05);
  EXPECT_GT(std::abs(middle.fov_y_degrees - first.fov_y_degrees), 5.0);
  for (const Object& object : scene.objects) EXPECT_TRUE(object.is_static());

  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  size_t straddling = 0, behind = 0;
  for (size_t o = 0; o < cs.objects.size(); ++o) {
    const CameraSpaceObject& object = cs.objects[o];
    for (size_t k = 0; k < object.key_times.size(); ++k) {
      const std::span<const Vec3> p = object.key(k);
      for (const Triangle& tri : cs.triangles(o)) {
        const double z_min = std::min({p[tri[0]].z(), p[tri[1]].z(), p[tri[2]].z()});
        const double z_max = std::max({p[tri[0]].z(), p[tri[1]].z(), p[tri[2]].z()});
        straddling += z_min < 0 && z_max > 0;
        behind += z_max < 0;
      }
    }
  }
  EXPECT_GT(straddling, 0u);  // a triangle with vertices on both sides of the eye plane at a key
  EXPECT_GT(behind, 0u);      // and triangles wholly behind the camera
}

TEST(Procedural, StaticMovingHasStaticBackgroundAndAnObjectThatComesAndGoes) {
  const Scene scene = make_builtin_scene("static-moving", {{"triangles", 3000}});
  size_t static_objects = 0, moving_objects = 0, transient = 0;
  for (const Object& object : scene.objects) {
    if (object.key_count() == 1) ++static_objects;
    if (!object.is_static()) ++moving_objects;
    if (object.appear > scene.time_begin && object.disappear < scene.time_end) {
      ++transient;
      EXPECT_NEAR(object.appear, scene.time_end / 3, 1e-12);
      EXPECT_NEAR(object.disappear, 0.75 * scene.time_end, 1e-12);
    }
  }
  EXPECT_EQ(static_objects, 2u);
  EXPECT_EQ(moving_objects, 2u);
  EXPECT_EQ(transient, 1u);
  EXPECT_EQ(scene.camera.keys.size(), 1u);
}

}  // namespace
}  // namespace kinray
