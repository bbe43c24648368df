// Motion blur with lights (renderer/motion_blur/shutter_shadows.h): a shadow sweeping over a
// pixel at constant speed against its exact time average, the window tree's answers against
// every triangle tested, the light mask of a blurred frame against the sharp frame's, and a
// built-in scene with two lights against an Embree reference with many samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "kinetic/tree/window_bvh.h"
#include "renderer/backends/backend.h"
#include "renderer/backends/grid_meshes.h"
#include "renderer/shadows/lighting.h"
#include "scenes/camera_space.h"
#include "scenes/model_import.h"
#include "scenes/procedural.h"
#include "tests/renderer/analytic_scenes.h"
#include "tests/renderer/motion_blur/blur_config.h"
#include "verification/image_diff.h"
#include "verification/shutter_error.h"

namespace kinray {
namespace {

using test::blur_config;

constexpr int kW = 64, kH = 32;

/// A ground quad at depth 4 filling the image, lit along the view by a directional light, and a
/// slab `width` wide (x from -6 + 12 t to -6 + width + 12 t, y in [1, 1.5]) at depth 2 sliding
/// right at constant speed. The light's rays are parallel to the view axis, so the slab's shadow on
/// the ground is its own x and y range: the ground point at x = X is in shadow for t in
/// [(X + 6 - width) / 12, (X + 6) / 12]. Rows 10 and 11 see the ground there (at y in [1, 1.5]) and
/// never the slab (their rays cross depth 2 at y < 0.75). The ground's diagonal crosses those rows
/// left of the shadow's path: a shadow ray that leaves from a shared edge may meet the neighbour
/// (a tie of every backend).
Scene sweeping_shadow(double width) {
  const Object ground = test::camera_space_object(
      "ground", {{0, 1, 2}, {0, 2, 3}},
      {{Vec3(-20, -20, 4), Vec3(20, -20, 4), Vec3(20, 30, 4), Vec3(-20, 30, 4)}});
  auto slab = [&](double left) {
    return std::vector<Vec3>{Vec3(left, 1, 2), Vec3(left + width, 1, 2), Vec3(left + width, 1.5, 2),
                             Vec3(left, 1.5, 2)};
  };
  const Object occluder =
      test::camera_space_object("slab", {{0, 1, 2}, {0, 2, 3}}, {slab(-6), slab(6)}, {0.0, 1.0});
  Scene scene = test::analytic_scene({ground, occluder});
  Light light;
  light.kind = Light::Kind::directional;
  light.direction = Vec3(0, 0, -1);  // shining away from the camera, along its view
  scene.lights = {light};
  return scene;
}

/// Renders sweeping_shadow(width) over the window [0.3, 0.7] with the kinetic backend and Embree
/// at 64 samples, and checks rows 10 and 11 against the exact time average. Returns how many pixels
/// are in shadow for part of the window only.
int check_sweeping_shadow(double width) {
  const Scene scene = sweeping_shadow(width);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const CameraSpaceLights lights(scene);
  auto kinetic = make_backend("kinetic", cs, blur_config(kW, kH));
  auto embree = make_backend("embree", cs, blur_config(kW, kH, 64, false));
  const ShutterWindow window{0.3, 0.5, 0.7};
  Frame blurred, sampled;
  kinetic->render_shutter(window, blurred);
  embree->render_shutter(window, sampled);
  const PixelRays image{kW, kH};
  int partly = 0;
  for (int j = 10; j <= 11; ++j) {
    for (int i = 0; i < kW; ++i) {
      const size_t p = blurred.index(i, j);
      EXPECT_EQ(blurred.object[p], 0u) << "pixel " << i << ", " << j << " sees the ground";
      const Vec3 d = image.direction(i, j);
      const double x = d.x() / d.z() * 4;  // the ground point it sees
      const double shadow_begin = std::max((x + 6 - width) / 12, window.open);
      const double shadow_end = std::min((x + 6) / 12, window.close);
      const double shadowed = std::max(0.0, shadow_end - shadow_begin) / window.length();
      if (shadowed > 0 && shadowed < 1) ++partly;
      const LitHit hit = lit_hit(cs, 0, blurred.prim[p], d, window.time);
      const std::vector<CameraSpaceLight> at = lights.at(window.time);
      const Color lit = lit_color(hit, at, 1u), dark = lit_color(hit, at, 0u);
      EXPECT_GT(lit.x() - dark.x(), 0.1f);
      const double expected = lit.x() * (1 - shadowed) + dark.x() * shadowed;
      // The change times are found to 1e-6 of the window.
      EXPECT_NEAR(blurred.color[p].x(), expected, 1e-5)
          << "width " << width << ", pixel " << i << ", " << j;
      // 64 stratified samples: at most the two strata holding a change are off.
      EXPECT_NEAR(sampled.color[p].x(), expected, 2.0 / 64 * (lit.x() - dark.x()) + 1e-6)
          << "width " << width << ", pixel " << i << ", " << j;
    }
  }
  return partly;
}

TEST(ShutterShadows, AShadowEdgeSweepingOverAPixelIsIntegratedExactly) {
  // A wide slab: each pixel's shadow ends once inside the window.
  EXPECT_GE(check_sweeping_shadow(30), 30);
}

TEST(ShutterShadows, AShadowCrossingAPixelIsIntegratedExactlyWhenItOutlastsTheProbeSpacing) {
  // A slab 2.5 wide: each pixel is in shadow for 0.52 of the window, longer than the largest gap
  // between its probes (the ends and four Gauss-Legendre nodes: 0.34 of the window), so both of
  // its changes are found. A shadow shorter than that gap may fall between two probes and be
  // missed (shutter_shadows.h).
  EXPECT_GE(check_sweeping_shadow(2.5), 30);
}

TEST(ShutterShadows, TheWindowTreeAnswersAsEveryTriangleTested) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 800}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  WindowBvh tree(grid_meshes(cs));
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  int blocked = 0, free = 0, hinted = 0;
  uint32_t hint = kNoNode;  // the last ray's occluder: right for some rays, wrong for most
  for (const auto& [open, close] : std::vector<std::pair<double, double>>{{0.1, 0.3}, {0.9, 1.4}}) {
    tree.sweep(open, close);
    for (int r = 0; r < 2000; ++r) {
      // Some rays at the window's ends and at the ends of its parts, each with its own boxes.
      const double t = r % 40 == 0 ? open + (close - open) * double(r / 40 % 5) / 4
                                   : open + (close - open) * (unit(random) + 1) / 2;
      TreeRay ray;
      ray.origin = Vec3(unit(random) * 0.5, unit(random) * 0.5, 3 + unit(random));
      ray.direction = Vec3(unit(random), unit(random), unit(random));
      ray.s_max = r % 2 ? 1.0 : kInfinity;
      const bool answer = tree.occluded(ray, t);
      ASSERT_EQ(answer, tree.occluded_brute_force(ray, t)) << "ray " << r << " at " << t;
      (answer ? blocked : free) += 1;
      // With a hint, the same answer, and the triangle named meets the ray.
      const uint32_t occluder = tree.occluder(ray, t, hint);
      ASSERT_EQ(occluder != kNoNode, answer) << "ray " << r << " at " << t;
      if (occluder != kNoNode) {
        // The hint is answered first: only when it meets the ray, so the occluder does.
        ASSERT_EQ(tree.occluder(ray, t, occluder), occluder);
        // A ray of the next instant, barely turned, is mostly answered by the same triangle.
        TreeRay next = ray;
        next.direction = Vec3(ray.direction.x() * (1 + 1e-9), ray.direction.y(), ray.direction.z());
        const uint32_t again = tree.occluder(next, std::min(t + 1e-9, close), occluder);
        ASSERT_EQ(again != kNoNode, tree.occluded_brute_force(next, std::min(t + 1e-9, close)));
        hinted += again == occluder;
      }
      hint = occluder;
    }
  }
  EXPECT_GT(blocked, 200);  // both answers occur
  EXPECT_GT(free, 200);
  EXPECT_GT(hinted, blocked * 9 / 10);
}

/// wavy-sphere (2,000 triangles) lit by a point light and a directional one.
Scene wavy_sphere_with_two_lights() {
  Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  Light point;
  point.position = Vec3(2, 3, 4);
  Light sun;
  sun.kind = Light::Kind::directional;
  sun.direction = Vec3(1, -1, -1).normalized();
  scene.lights = {point, sun};
  return scene;
}

TEST(ShutterShadows, TheLightMaskIsTheSharpFramesAtTheFrameTime) {
  const Scene scene = wavy_sphere_with_two_lights();
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const CameraSpaceLights lights(scene);
  for (const char* name : {"kinetic", "embree"}) {
    auto blurred_backend = make_backend(name, cs, blur_config(48, 48));
    auto sharp_backend = make_backend(name, cs, blur_config(48, 48));
    Frame blurred, sharp;
    blurred_backend->render_shutter({0.95, 1.0, 1.05}, blurred);
    sharp_backend->render(1.0, sharp);
    shade_frame_lit(cs, lights, *sharp_backend->shadow_tracer(), sharp, 2);
    EXPECT_EQ(blurred.object, sharp.object) << name;
    EXPECT_EQ(blurred.lit, sharp.lit) << name;
    EXPECT_GT(std::count(sharp.lit.begin(), sharp.lit.end(), 1u) +
                  std::count(sharp.lit.begin(), sharp.lit.end(), 2u),
              0)
        << "some pixel is lit by one light only";
  }
}

TEST(ShutterShadows, KineticIsAsCloseToTheReferenceAsManySamples) {
  const Scene scene = wavy_sphere_with_two_lights();
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const test::BlurErrors errors = test::blur_errors(cs, {0.9, 1.0, 1.1}, 48, 16);
  const ColorError &kinetic_error = errors.kinetic, &sampled_error = errors.sampled;
  EXPECT_TRUE(ShutterTolerance{}.met(kinetic_error)) << std::sqrt(kinetic_error.mse);
  EXPECT_LT(kinetic_error.mse * 4, sampled_error.mse);
}

// A skinned model turning under a point light: its smooth normals cross the terminator inside
// front intervals, a kink in the shading that the intervals are cut at (lit_side_mask), so the
// kinetic frame is as close to a 1024-sample reference as Embree at 256 samples or closer (with
// the kink inside the Gauss-Legendre rule: RMSE 3.0e-5 against 5.7e-6, Embree-256 1.8e-5).
TEST(ShutterShadows, TheShadingTerminatorOfSmoothNormalsIsIntegratedAsSharply) {
  const std::string path = "/usr/share/assimp/models/X/Testwuson.X";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  Scene scene = load_model(path);
  Light point;
  point.position = Vec3(2, 3, 4);
  scene.lights = {point};
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  // The last of three frames over the run cycle (`diff --frames 3 --shutter 0.5`): the window is a
  // quarter of the frame interval, an eighth of the cycle, through which the legs swing across
  // the light's terminator.
  const double end = scene.key_times().back();
  const ShutterWindow window{end - end / 8, end, end + end / 8};
  const test::BlurErrors errors = test::blur_errors(cs, window, 96, 256);
  const ColorError &kinetic_error = errors.kinetic, &sampled_error = errors.sampled;
  EXPECT_LE(kinetic_error.mse, sampled_error.mse)
      << "kinetic RMSE " << std::sqrt(kinetic_error.mse) << ", Embree-256 "
      << std::sqrt(sampled_error.mse);
}

}  // namespace
}  // namespace kinray
