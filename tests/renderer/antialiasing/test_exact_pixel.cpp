// The exact box-filtered read-out (renderer/antialiasing/exact_pixel.h) on a built-in scene: each
// pixel's overlapping set found by brute force, its colour against the mean of 64 x 64 stratified
// samples of the same shading cast by brute force, within the samples' noise.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

#include "renderer/antialiasing/exact_pixel.h"
#include "scenes/model_import.h"
#include "scenes/procedural.h"
#include "tests/renderer/antialiasing/brute_force_squares.h"

namespace kinray {
namespace {

/// The exact frame of `scene` at t, each pixel's triangles by brute force (a superset: the
/// read-out must ignore the extra ones).
std::vector<Color> exact_colours(const CameraSpaceScene& scene, int width, int height, double t,
                                 const test::SceneTriangles& triangles) {
  ExactPixels::Stats stats;
  const std::vector<Color> colours =
      test::brute_force_exact_colours(scene, width, height, t, triangles, &stats);
  std::printf("%zu pixels: %zu inside one triangle, %.2f triangles, %.2f pieces, %.1f nodes each\n",
              stats.pixels, stats.covered_by_one, double(stats.triangles) / stats.pixels,
              double(stats.pieces) / stats.pixels, double(stats.nodes) / stats.pixels);
  EXPECT_EQ(stats.pixels, size_t(width) * size_t(height));
  EXPECT_GE(stats.nodes, 7 * stats.pieces);
  return colours;
}

std::vector<Color> sampled_colours(int width, int height, const test::SceneTriangles& triangles,
                                   int m, uint32_t seed) {
  const PixelRays image{width, height};
  std::vector<Color> out;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      std::mt19937 rng(seed * 1000003u + uint32_t(j * width + i));
      const PixelSquare s = pixel_square(image, i, j);
      out.push_back(test::sampled_colour(triangles, test::overlapping(triangles, s), s, m, rng));
    }
  return out;
}

/// The exact frame of `scene` at t against two 64 x 64-sample references with independent jitter,
/// which differ by sqrt(2) times the noise of one. The exact frame must differ from a reference by
/// that noise only: its RMSE below 1.3 x the noise estimate (plus 2e-5 for float rounding), and
/// its largest pixel error below 1.5 x the largest difference between the two references (plus
/// 1e-5). The noise sits on the few pixels an edge crosses (their stratified error is about the
/// colour step over 4096 per stratum the edge crosses), so the largest error is the pixel test,
/// the RMSE over all pixels the frame test.
void check_against_sampling(const CameraSpaceScene& scene, double t) {
  const test::SceneTriangles triangles = test::scene_triangles(scene, t);
  const std::vector<Color> exact = exact_colours(scene, 32, 24, t, triangles);
  const std::vector<Color> a = sampled_colours(32, 24, triangles, 64, 1);
  const std::vector<Color> b = sampled_colours(32, 24, triangles, 64, 2);
  const test::ImageError between = test::image_error(a, b);
  const double noise = between.rmse / std::sqrt(2.0);
  const test::ImageError error = test::image_error(exact, a);
  std::printf(
      "noise %.3g (references apart by at most %.3g), exact vs sampled: rmse %.3g max %.3g\n",
      noise, between.max, error.rmse, error.max);
  EXPECT_GT(noise, 0);
  EXPECT_LT(error.rmse, 1.3 * noise + 2e-5);
  EXPECT_LT(error.max, 1.5 * between.max + 1e-5);
  // Not trivially: the background and several colours are there.
  double spread = 0;
  for (const Color& c : exact) spread = std::max(spread, double((c - exact[0]).norm()));
  EXPECT_GT(spread, 0.1);
}

// wavy-sphere at 2000 triangles, 32 x 24: a pixel holds up to a dozen triangles, silhouettes
// against the background, and every shading gradient.
TEST(ExactPixel, WavySphereMatchesStratifiedSampling) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  check_against_sampling(CameraSpaceScene::build(scene), 0.37 * scene.key_times().back());
}

// Built-ins with what wavy-sphere lacks: a camera flying between pillars (triangles straddling
// the eye plane), spheres passing through each other (interpenetrating pairs), a cloth folding
// through itself, boxes orbiting in front of each other.
TEST(ExactPixel, BuiltinsMatchStratifiedSampling) {
  for (const char* name : {"flythrough", "crossing", "cloth-fold", "orbit"}) {
    SCOPED_TRACE(name);
    const Scene scene = make_builtin_scene(name, {{"triangles", 3000}});
    const auto& keys = scene.key_times();
    check_against_sampling(CameraSpaceScene::build(scene),
                           keys.front() + 0.43 * (keys.back() - keys.front()));
  }
}

// Where a triangle's vertex normals straddle the view, the headlight's |cos| has a kink inside
// the pixel: the fan triangles it crosses are halved and cut along its chord. The default
// (ExactPixels::Config::kink_depth) is within 2e-6 of nine halvings on flythrough, whose
// lintels and pillars have such triangles, and no halving is off by far more.
TEST(ExactPixel, KinksAreFollowed) {
  const Scene scene = make_builtin_scene("flythrough", {{"triangles", 3000}});
  const auto& keys = scene.key_times();
  const double t = keys.front() + 0.43 * (keys.back() - keys.front());
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const test::SceneTriangles triangles = test::scene_triangles(cs, t);
  const PixelRays image{32, 24};
  std::vector<std::vector<TriangleRef>> sets;
  for (int j = 0; j < 24; ++j)
    for (int i = 0; i < 32; ++i) {
      sets.emplace_back();
      for (size_t k : test::overlapping(triangles, pixel_square(image, i, j)))
        sets.back().push_back(triangles.refs[k]);
    }
  auto frame = [&](int depth) {
    ExactPixels::Config config;
    config.kink_depth = depth;
    ExactPixels pixels(cs, image, t, config);
    std::vector<Color> out;
    for (int j = 0; j < 24; ++j)
      for (int i = 0; i < 32; ++i) out.push_back(pixels.colour(i, j, sets[size_t(j * 32 + i)]));
    return out;
  };
  const std::vector<Color> deep = frame(9);
  EXPECT_LT(test::image_error(frame(ExactPixels::Config{}.kink_depth), deep).max, 2e-6);
  EXPECT_GT(test::image_error(frame(0), deep).max, 1e-4);  // the kinks are there
}

// A textured box (glTF sample model): the texels slide under the pixels, the read-out cuts each
// textured piece finer (ExactPixels::Config::textured_subdivision).
TEST(ExactPixel, TexturedBoxMatchesStratifiedSampling) {
  const std::filesystem::path path =
      "/usr/share/assimp/models/glTF2/BoxTextured-glTF/BoxTextured.gltf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  const Scene scene = load_model(path.string());
  ASSERT_FALSE(scene.textures.empty());
  check_against_sampling(CameraSpaceScene::build(scene), scene.key_times().front());
}

// A pixel with nothing over it is the background exactly; one deep inside a triangle facing the
// camera is close to its centre colour (the headlight varies little over a pixel).
TEST(ExactPixel, BackgroundAndInteriorPixels) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 400}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const PixelRays image{32, 24};
  EXPECT_EQ(exact_pixel_colour(cs, image, 0, 0, 0.0, {}), kBackgroundColor);
  const test::SceneTriangles triangles = test::scene_triangles(cs, 0.0);
  std::vector<TriangleRef> all = triangles.refs;
  const int i = 16, j = 12;
  const Color exact = exact_pixel_colour(cs, image, i, j, 0.0, all);
  const long k = test::nearest(triangles, test::overlapping(triangles, pixel_square(image, i, j)),
                               image.direction(i, j));
  ASSERT_GE(k, 0);
  const Color centre = shade_hit(cs, image, i, j, triangles.refs[size_t(k)].object,
                                 triangles.refs[size_t(k)].prim, 0.0);
  EXPECT_LT((exact - centre).norm(), 0.05);
  // The same set held as the kinetic square sets hold it ({mesh, triangle}, in another order),
  // read through to_ref: the same colour, bit for bit.
  struct SquareMember {
    uint32_t mesh = 0, triangle = 0;
  };
  std::vector<SquareMember> members;
  for (auto it = all.rbegin(); it != all.rend(); ++it) members.push_back({it->object, it->prim});
  ExactPixels pixels(cs, image, 0.0);
  const Color read =
      pixels.colour(i, j, std::span<const SquareMember>(members), [](const SquareMember& m) {
        return TriangleRef{m.mesh, m.triangle};
      });
  EXPECT_EQ(read, exact);
}

}  // namespace
}  // namespace kinray
