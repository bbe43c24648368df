// Motion blur (renderer/motion_blur/shutter.h, kinetic_shutter.h, embree_motion_blur.h): the Gauss-Legendre
// rules and the windows of a schedule; a quad sliding across the image against the exact time
// average; still frames identical to the sharp frames; overlapping windows; and the kinetic
// frames of a built-in scene, audited, against an Embree reference with many time samples.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "renderer/backends/backend.h"
#include "renderer/motion_blur/shutter.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"
#include "scenes/procedural.h"
#include "tests/rejected_where.h"
#include "tests/renderer/analytic_scenes.h"
#include "tests/renderer/motion_blur/blur_config.h"
#include "verification/image_diff.h"
#include "verification/shutter_error.h"

namespace kinray {
namespace {

using test::blur_config;

TEST(GaussLegendre, IntegratesPolynomialsOfDegree2nMinus1Exactly) {
  for (int n = 1; n <= 8; ++n) {
    const GaussLegendre rule = gauss_legendre(n);
    ASSERT_EQ(rule.nodes.size(), size_t(n));
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      double sum = 0;
      for (int k = 0; k < n; ++k)
        sum += rule.weights[size_t(k)] * std::pow(rule.nodes[size_t(k)], degree);
      const double exact = degree % 2 ? 0.0 : 2.0 / (degree + 1);
      EXPECT_NEAR(sum, exact, 1e-13) << "n " << n << " degree " << degree;
    }
  }
  // And not degree 2n: the order is what it claims.
  const GaussLegendre two = gauss_legendre(2);
  EXPECT_GT(std::abs(two.weights[0] * std::pow(two.nodes[0], 4) * 2 - 0.4), 1e-3);
}

TEST(GaussLegendre, CellsTileTheIntervalInNodeOrderEachAsLongAsItsWeight) {
  for (int n = 1; n <= 16; ++n) {
    const GaussLegendre rule = gauss_legendre(n);
    ASSERT_EQ(rule.cell_lo.size(), size_t(n));
    double covered = 0;
    for (int k = 0; k < n; ++k) {
      const size_t i = size_t(k);
      EXPECT_NEAR(rule.cell_hi[i] - rule.cell_lo[i], rule.weights[i], 1e-13);
      EXPECT_LT(rule.cell_lo[i], rule.nodes[i]);  // each cell holds its node
      EXPECT_GT(rule.cell_hi[i], rule.nodes[i]);
      covered += rule.cell_hi[i] - rule.cell_lo[i];
      // Cells meet: every inner end is another cell's start.
      if (rule.cell_hi[i] < 1)
        EXPECT_NE(std::find(rule.cell_lo.begin(), rule.cell_lo.end(), rule.cell_hi[i]),
                  rule.cell_lo.end());
    }
    EXPECT_NEAR(covered, 2, 1e-13);
  }
}

TEST(ShutterWindows, CentredOnEachFrameAndClippedToTheShot) {
  const std::vector<double> keys = {0, 0.5, 1};
  const auto regular = shutter_windows(std::vector<double>{0, 0.25, 0.5, 0.75, 1}, keys, 0.5);
  ASSERT_EQ(regular.size(), 5u);
  EXPECT_DOUBLE_EQ(regular[0].open, 0);  // clipped: the shot starts at 0
  EXPECT_DOUBLE_EQ(regular[0].close, 0.0625);
  EXPECT_DOUBLE_EQ(regular[2].open, 0.4375);
  EXPECT_DOUBLE_EQ(regular[2].close, 0.5625);
  EXPECT_DOUBLE_EQ(regular[4].close, 1);
  // Irregular: the interval of a frame is half the distance between its neighbours.
  const auto irregular = shutter_windows(std::vector<double>{0, 0.4, 0.5, 1}, keys, 1.0);
  EXPECT_DOUBLE_EQ(irregular[1].close, 0.4 + 0.25 / 2);
  EXPECT_DOUBLE_EQ(irregular[2].open, 0.5 - 0.3 / 2);
  EXPECT_GT(irregular[1].close, irregular[2].open);  // overlapping windows
  // A lone frame: its key interval.
  const auto lone = shutter_windows(std::vector<double>{0.7}, keys, 0.5);
  EXPECT_DOUBLE_EQ(lone[0].open, 0.7 - 0.125);
  EXPECT_DOUBLE_EQ(lone[0].close, 0.7 + 0.125);
  // S = 0: windows of length 0.
  EXPECT_EQ(shutter_windows(std::vector<double>{0.3}, keys, 0)[0].length(), 0);
}

TEST(ShutterParams, ValidationNamesTheFlag) {
  EXPECT_EQ(test::rejected_where(ShutterParams{0.5, 16, 0}), "(accepted)");
  EXPECT_EQ(test::rejected_where(ShutterParams{1.5, 16, 0}), "--shutter");
  EXPECT_EQ(test::rejected_where(ShutterParams{-0.1, 16, 0}), "--shutter");
  EXPECT_EQ(test::rejected_where(ShutterParams{std::nan(""), 16, 0}), "--shutter");
  EXPECT_EQ(test::rejected_where(ShutterParams{0.5, 0, 0}), "--shutter-samples");
  EXPECT_EQ(test::rejected_where(ShutterParams{0.5, 16, 17}), "--shutter-order");
}

/// A quad at depth 2 whose left edge slides from column 10 to column 50 of a 64 x 32 image
/// between t = 0 and t = 1 (vertical edges, so a pixel centre is covered from the time the edge
/// passes it), seen face on: its colour at a pixel does not change while it covers it.
Scene sliding_quad(bool moving) {
  constexpr int kW = 64, kH = 32;
  const double z = 2;
  auto quad = [&](double left) {
    return std::vector<Vec3>{test::on_ray(left, 4, z, kW, kH), test::on_ray(63.5, 4, z, kW, kH),
                             test::on_ray(63.5, 28, z, kW, kH), test::on_ray(left, 28, z, kW, kH)};
  };
  if (!moving)
    return test::analytic_scene(
        {test::camera_space_object("quad", {{0, 1, 2}, {0, 2, 3}}, {quad(30.3)})});
  return test::analytic_scene({test::camera_space_object("quad", {{0, 1, 2}, {0, 2, 3}},
                                                         {quad(50.25), quad(10.25)}, {0.0, 1.0})});
}

TEST(MotionBlur, KineticMatchesTheExactAverageOfASlidingQuad) {
  const Scene scene = sliding_quad(true);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  auto kinetic = make_backend("kinetic", cs, blur_config(64, 32));
  auto embree = make_backend("embree", cs, blur_config(64, 32, 64, false));
  const ShutterWindow window{0.3, 0.4, 0.5};
  Frame blurred, sampled;
  kinetic->render_shutter(window, blurred);
  embree->render_shutter(window, sampled);
  const PixelRays image{64, 32};
  const int j = 16;
  for (int i = 0; i < 64; ++i) {
    // The left edge is at column 50.25 - 40 t (in pixel units); centre i + 0.5 is covered once
    // the edge is left of it: from t_c = (50.25 - (i + 0.5)) / 40.
    const double t_c = (50.25 - (i + 0.5)) / 40;
    const double covered =
        std::clamp((window.close - std::max(t_c, window.open)) / window.length(), 0.0, 1.0);
    const Color quad = shade_hit(cs, image, i, j, 0, 0, 0.4);
    const Color expected =
        (quad.cast<double>() * covered + kBackgroundColor.cast<double>() * (1 - covered)).cast<float>();
    const size_t p = blurred.index(i, j);
    EXPECT_NEAR(blurred.color[p].x(), expected.x(), 1e-6) << "column " << i;
    EXPECT_NEAR(blurred.color[p].z(), expected.z(), 1e-6) << "column " << i;
    // 64 stratified samples: at most one stratum straddles the crossing.
    EXPECT_NEAR(sampled.color[p].x(), expected.x(), 1.0 / 64 + 1e-6) << "column " << i;
    // The id buffer is the sharp frame's at the frame time.
    const bool front_at_time = t_c <= 0.4;
    EXPECT_EQ(blurred.object[p], front_at_time ? 0u : kNoHit) << "column " << i;
  }
}

TEST(MotionBlur, ATextureSlidingManyTexelsAWindowIsAveragedAlongItsPath) {
  // A white quad at depth 2, seen face on, 60 wide with u from 0 to 1 across it, slides by 40
  // along x over the shot; its 256 x 4 texture of random texels crosses about 17 texels under a
  // pixel in the window [0.45, 0.55]. Face on and translating, the headlight term is constant
  // in time and u linear in it, so the exact blurred colour is the headlight times the texture's
  // mean along the path (Texture::path_average, itself checked against dense sampling).
  constexpr int kSize = 32;
  Scene scene = test::analytic_scene(
      {test::camera_space_object("quad", {{0, 1, 2}, {0, 2, 3}},
                                 {{{-30, -3, 2}, {30, -3, 2}, {30, 3, 2}, {-30, 3, 2}},
                                  {{10, -3, 2}, {70, -3, 2}, {70, 3, 2}, {10, 3, 2}}},
                                 {0.0, 1.0})});
  Texture texture;
  texture.width = 256;
  texture.height = 4;
  uint64_t state = 12345;
  for (int k = 0; k < texture.width * texture.height; ++k) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    const auto level = float(0.2 + 0.8 * double(state >> 40) / double(1ull << 24));
    texture.texels.push_back(Color(level, 1.0f - level / 2, 0.5f));
  }
  scene.textures.push_back(texture);
  scene.materials.push_back(Material{"textured", Color(1, 1, 1), 0});
  scene.objects[0].material = 1;
  scene.objects[0].uvs = {Vec2f(0, 0), Vec2f(1, 0), Vec2f(1, 1), Vec2f(0, 1)};
  scene.validate("textured quad");
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const ShutterWindow window{0.45, 0.5, 0.55};
  auto kinetic = make_backend("kinetic", cs, blur_config(kSize, kSize));
  auto sampled = make_backend("embree", cs, blur_config(kSize, kSize, 16, false));
  Frame blurred, samples;
  kinetic->render_shutter(window, blurred);
  sampled->render_shutter(window, samples);
  const PixelRays image{kSize, kSize};
  double worst = 0, sampled_worst = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const Vec3 d = image.direction(i, j);
      const auto uv = [&](double t) {
        return Vec2f(float((2 * d.x() - (-30 + 40 * t)) / 60), float((2 * d.y() + 3) / 6));
      };
      const float lambert = std::abs(view_direction(d, cs.tan_half_fov(0.5)).z());
      const Color expected =
          texture.path_average(uv(window.open), uv(window.close)) * (kAmbient + kDiffuse * lambert);
      const size_t p = blurred.index(i, j);
      worst = std::max(worst, double((blurred.color[p] - expected).cwiseAbs().maxCoeff()));
      sampled_worst =
          std::max(sampled_worst, double((samples.color[p] - expected).cwiseAbs().maxCoeff()));
    }
  EXPECT_LT(worst, 2e-5);
  // Sixteen time samples of 17 texels are far off: the texture is really crossed.
  EXPECT_GT(sampled_worst, 100 * worst);
}

TEST(MotionBlur, StillFramesAreIdenticalToTheSharpFrames) {
  const Scene scene = sliding_quad(false);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  for (const char* name : {"kinetic", "embree"}) {
    auto blurred_backend = make_backend(name, cs, blur_config(64, 32));
    auto sharp_backend = make_backend(name, cs, blur_config(64, 32));
    Frame blurred, sharp;
    blurred_backend->render_shutter({0.2, 0.5, 0.8}, blurred);
    sharp_backend->render(0.5, sharp);
    shade_frame(cs, sharp, 2);
    EXPECT_EQ(blurred.object, sharp.object) << name;
    EXPECT_EQ(blurred.prim, sharp.prim) << name;
    EXPECT_EQ(blurred.depth, sharp.depth) << name;
    EXPECT_TRUE(blurred.color == sharp.color) << name;
  }
}

TEST(MotionBlur, OverlappingWindowsGiveTheFramesOfFreshGrids) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 400}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const std::vector<ShutterWindow> windows = {
      {0.10, 0.15, 0.20}, {0.12, 0.17, 0.22}, {0.30, 0.31, 0.32}};
  auto shared = make_backend("kinetic", cs, blur_config(40, 40));
  for (const ShutterWindow& w : windows) {
    auto fresh = make_backend("kinetic", cs, blur_config(40, 40));
    Frame a, b;
    shared->render_shutter(w, a);
    fresh->render_shutter(w, b);
    EXPECT_EQ(a.object, b.object);
    EXPECT_LT(compare_colors(a, b).max_error, 1e-6);
  }
}

TEST(MotionBlur, KineticIsAsCloseToTheReferenceAsManySamples) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const test::BlurErrors errors = test::blur_errors(cs, {0.95, 1.0, 1.05}, 48, 16);
  const ColorError &kinetic_error = errors.kinetic, &sampled_error = errors.sampled;
  const Frame& k = errors.kinetic_frame;
  EXPECT_TRUE(ShutterTolerance{}.met(kinetic_error)) << std::sqrt(kinetic_error.mse);
  EXPECT_LT(kinetic_error.mse * 4, sampled_error.mse);
  // The blur is real: the blurred frame is not the sharp one.
  Frame sharp;
  auto sharp_backend = make_backend("kinetic", cs, blur_config(48, 48));
  sharp_backend->render(1.0, sharp);
  shade_frame(cs, sharp, 2);
  EXPECT_EQ(sharp.object, k.object);
  EXPECT_GT(compare_colors(sharp, k).max_error, 0.05);
}

}  // namespace
}  // namespace kinray
