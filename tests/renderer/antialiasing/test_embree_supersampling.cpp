// Embree's supersampled antialiasing (BackendConfig::aa_samples, renderer/antialiasing/
// embree_supersampling.h): one sample is the centre-ray frame bit for bit; the error against a
// 1024-sample frame falls as the samples grow; and, the key test, the exact read-out of
// renderer/antialiasing/exact_pixel.h agrees with 4096 samples within their noise.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <vector>

#include "renderer/antialiasing/exact_pixel.h"
#include "renderer/antialiasing/pixel_samples.h"
#include "renderer/backends/backend.h"
#include "renderer/backends/embree_backend.h"
#include "renderer/job/render_job.h"
#include "renderer/shading.h"
#include "renderer/shadows/lighting.h"
#include "scenes/procedural.h"
#include "tests/rejected_where.h"
#include "tests/renderer/antialiasing/brute_force_squares.h"
#include "util/input_error.h"

namespace kinray {
namespace {

constexpr int kWidth = 32, kHeight = 24;

BackendConfig aa_config(int samples) {
  BackendConfig c;
  c.width = kWidth;
  c.height = kHeight;
  c.threads = 2;
  c.aa_samples = samples;
  return c;
}

Frame supersampled(const CameraSpaceScene& scene, int samples, double t) {
  const std::unique_ptr<Backend> backend = make_backend("embree", scene, aa_config(samples));
  Frame frame;
  backend->render_supersampled(t, frame);
  return frame;
}

bool same_bits(const std::vector<Color>& a, const std::vector<Color>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Color)) == 0;
}

TEST(PixelSamples, StratifiedInsideTheSquareAndFixedPerPixel) {
  const PixelSquare s{-0.5, 0.5, 1.0, 3.0};
  for (int k = 0; k < 16; ++k) {
    const Vec2 p = pixel_sample(s, 7, k, 4);
    EXPECT_GE(p.x(), s.x0 + 0.25 * (k % 4));
    EXPECT_LE(p.x(), s.x0 + 0.25 * (k % 4 + 1));
    EXPECT_GE(p.y(), s.y0 + 0.5 * (k / 4));
    EXPECT_LE(p.y(), s.y0 + 0.5 * (k / 4 + 1));
    EXPECT_EQ(p, pixel_sample(s, 7, k, 4));
    EXPECT_NE(p, pixel_sample(s, 8, k, 4));
  }
  EXPECT_EQ(sample_grid_side(1), 1);
  EXPECT_EQ(sample_grid_side(4096), 64);
  EXPECT_EQ(sample_grid_side(8), 0);
}

TEST(EmbreeSupersampling, RejectsCountsThatAreNotSquares) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 100}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  for (int bad : {0, 2, 8, -4}) {
    try {
      (void)make_backend("embree", cs, aa_config(bad));
      ADD_FAILURE() << bad << " accepted";
    } catch (const OptionError& e) {
      EXPECT_EQ(e.where(), "aa_samples");
    }
  }
  EXPECT_THROW((void)make_backend("kinetic", cs, aa_config(4)), OptionError);
}

// One sample per pixel is the centre ray: the frame render() and shade_frame give, bit for bit,
// with the headlight and with a point and a directional light and their shadow rays.
TEST(EmbreeSupersampling, OneSampleIsTheCentreFrame) {
  for (bool lit : {false, true}) {
    Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 400}});
    Light sun;
    sun.kind = Light::Kind::directional;
    sun.direction = Vec3(1, -1, -1).normalized();
    if (lit) scene.lights = {Light{Light::Kind::point, Vec3(3, 4, 5)}, sun};
    const CameraSpaceScene cs = CameraSpaceScene::build(scene);
    const double t = 0.3;
    const Frame one = supersampled(cs, 1, t);
    const std::unique_ptr<Backend> backend = make_backend("embree", cs, aa_config(1));
    Frame centre;
    backend->render(t, centre);
    if (lit)
      shade_frame_lit(cs, CameraSpaceLights(scene), *backend->shadow_tracer(), centre, 2);
    else
      shade_frame(cs, centre, 2);
    EXPECT_TRUE(same_bits(one.color, centre.color)) << (lit ? "lit" : "headlight");
    EXPECT_EQ(one.object, centre.object);
    EXPECT_EQ(one.lit, centre.lit);
  }
}

// Stratified sampling of a pixel whose edges cross it: the error falls by about 2 (N^-1/2) to 2.8
// (N^-3/4, edges) per 4x samples. Against a 1024-sample frame (whose own noise is a quarter of
// 64's), each step from 4 to 16 to 64 samples must cut the RMSE by at least 1.6.
TEST(EmbreeSupersampling, ConvergesWithTheSampleCount) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const double t = 0.5;
  const std::vector<Color> reference = supersampled(cs, 1024, t).color;
  double previous = 0;
  for (int n : {4, 16, 64}) {
    const double rmse = test::image_error(supersampled(cs, n, t).color, reference).rmse;
    std::printf("%d samples: rmse %.3g\n", n, rmse);
    if (previous > 0) EXPECT_GT(previous / rmse, 1.6) << n << " samples";
    previous = rmse;
  }
}

// The samples traced in packets (every width this machine's Embree has) hit what single rays hit:
// the frames are bit for bit the same.
TEST(EmbreeSupersampling, PacketsAgreeWithSingleRays) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const double t = 0.5;
  const Frame single = supersampled(cs, 16, t);
  for (int packet : embree_packet_widths()) {
    BackendConfig c = aa_config(16);
    c.embree_packet = packet;
    const std::unique_ptr<Backend> backend = make_backend("embree", cs, c);
    Frame frame;
    backend->render_supersampled(t, frame);
    EXPECT_TRUE(same_bits(frame.color, single.color)) << packet;
  }
}

// With a light, every sample traces its shadow ray: the frame converges as the headlight's does
// (4 to 64 samples against 1024), is not the headlight's, and keeps the centre rays' light mask.
TEST(EmbreeSupersampling, LitSamplesConverge) {
  Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  scene.lights = {Light{Light::Kind::point, Vec3(3, 4, 5)}};
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const double t = 0.5;
  const Frame reference = supersampled(cs, 1024, t);
  const Frame centre = supersampled(cs, 1, t);
  EXPECT_EQ(reference.lit, centre.lit);
  double previous = 0;
  for (int n : {4, 16, 64}) {
    const double rmse = test::image_error(supersampled(cs, n, t).color, reference.color).rmse;
    if (previous > 0) EXPECT_GT(previous / rmse, 1.6) << n << " samples";
    previous = rmse;
  }
  Scene unlit = scene;
  unlit.lights.clear();
  const CameraSpaceScene unlit_cs = CameraSpaceScene::build(unlit);
  EXPECT_GT(test::image_error(supersampled(unlit_cs, 1024, t).color, reference.color).rmse, 1e-2);
}

// The render job passes RenderParams::aa_samples to the backend and lets it shade; it refuses
// counts that are not squares, naming the field; with motion blur it samples in (x, y, t).
TEST(EmbreeSupersampling, RenderJobSupersamples) {
  RenderParams params;
  params.scene = "wavy-sphere:triangles=400";
  params.backend = "embree";
  params.width = kWidth;
  params.height = kHeight;
  params.frames = 2;
  params.threads = 2;
  params.aa_samples = 16;
  RenderJob job(params);
  std::unique_ptr<Backend> backend = job.make_backend();
  Frame frame;
  job.render_frame(*backend, 1, frame);
  const Frame direct = supersampled(job.camera_space(), 16, job.frame_times()[1]);
  EXPECT_TRUE(same_bits(frame.color, direct.color));
  EXPECT_EQ(frame.object, direct.object);
  EXPECT_EQ(test::rejected_where(params), "(accepted)");
  params.aa_samples = 12;
  EXPECT_EQ(test::rejected_where(params), "aa_samples");
  params.aa_samples = 4;
  params.shutter.shutter = 0.5;
  EXPECT_EQ(test::rejected_where(params), "(accepted)");
}

// The key test: the exact read-out, every pixel's triangles found by brute force, against Embree
// with 4096 samples per pixel. Their difference must be the samples' noise, estimated against a
// brute-force 4096-sample frame with independent jitter (the two differ by sqrt(2) times it):
// the RMSE below 1.5 x that noise (plus 3e-5 for Embree's float vertices and float colours), the
// largest pixel error below 1.5 x the largest difference between the two sampled frames (plus
// 2e-5). Measured: noise 2.0e-5, RMSE 2.4e-5, largest error 3.4e-4.
TEST(EmbreeSupersampling, ExactReadOutAgreesWith4096Samples) {
  const Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const double t = 0.5;
  const test::SceneTriangles triangles = test::scene_triangles(cs, t);
  const PixelRays image{kWidth, kHeight};
  Frame exact;
  exact.resize(kWidth, kHeight);
  exact.time = t;
  std::vector<Color> brute;
  std::vector<std::vector<TriangleRef>> sets(exact.pixel_count());
  for (int j = 0; j < kHeight; ++j)
    for (int i = 0; i < kWidth; ++i) {
      const PixelSquare s = pixel_square(image, i, j);
      const std::vector<size_t> candidates = test::overlapping(triangles, s);
      for (size_t k : candidates) sets[exact.index(i, j)].push_back(triangles.refs[k]);
      std::mt19937 rng(uint32_t(exact.index(i, j)) * 7919u + 17u);
      brute.push_back(test::sampled_colour(triangles, candidates, s, 64, rng));
    }
  exact_frame_colours(
      cs, exact,
      [&](int i, int j) { return std::span<const TriangleRef>(sets[exact.index(i, j)]); }, 2);
  const std::vector<Color> sampled = supersampled(cs, 4096, t).color;
  const test::ImageError between = test::image_error(sampled, brute);
  const double noise = between.rmse / std::sqrt(2.0);
  const test::ImageError error = test::image_error(exact.color, sampled);
  std::printf(
      "noise %.3g (sampled frames apart by at most %.3g), exact vs embree 4096: rmse %.3g "
      "max %.3g\n",
      noise, between.max, error.rmse, error.max);
  EXPECT_LT(error.rmse, 1.5 * noise + 3e-5);
  EXPECT_LT(error.max, 1.5 * between.max + 2e-5);
}

}  // namespace
}  // namespace kinray
