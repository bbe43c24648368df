// Exact antialiasing with lights (renderer/antialiasing/exact_pixel.h, ExactLights): a shadow
// boundary through a pixel is resolved, not smeared by the quadrature. Known answer: a wall
// facing the camera, lit by a directional light, with an occluder above the view whose straight
// shadow edge crosses pixels at known places; a pixel's colour is the area-weighted mix of the
// lit and the shadowed colours (both constant over a flat wall under a directional light). Then
// a lit built-in scene against Embree's lit supersampling within the reference's noise.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "renderer/antialiasing/exact_pixel.h"
#include "renderer/backends/backend.h"
#include "renderer/job/render_job.h"
#include "renderer/shadows/brute_force_shadow_tracer.h"
#include "renderer/shadows/kinetic_shadow_tracer.h"
#include "scenes/procedural.h"
#include "tests/address_sanitizer.h"
#include "tests/renderer/antialiasing/brute_force_squares.h"
#include "tools/cli/light_flag.h"

namespace kinray {
namespace {

constexpr int kSize = 16;

/// A quad (world space) with corners a, b, c, d in order.
Object quad(const std::string& name, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  Object object;
  object.name = name;
  object.triangles = {{0, 1, 2}, {0, 2, 3}};
  object.key_times = {0.0};
  object.key_positions = {{a, b, c, d}};
  return object;
}

// The camera at the origin looks down -z with a 90 degree field of view, so the image point
// (u, v) is the ray (u, v, -1) of world space. The wall is z = -2, facing it. The occluder lies
// in z = -1.5 where y >= 1.6 + 0.3 x, above the wall's lit part; the light shines along
// (0, -2, -1): a wall point (x, y, -2) reaches the occluder's plane at (x, y + 1, -1.5), so it is
// in shadow where y + 1 >= 1.6 + 0.3 x, in the image (u, v) = (x, y) / 2 where
// v >= 0.3 + 0.3 u. The occluder itself is seen where v >= 1.6 / 1.5 + 0.3 u.
constexpr double kShadowV0 = 0.3, kShadowSlope = 0.3, kOccluderV0 = 1.6 / 1.5;

Scene wall_with_shadow_edge() {
  Scene scene;
  scene.name = "wall-with-shadow-edge";
  scene.objects = {
      quad("wall", Vec3(-10, -10, -2), Vec3(10, -10, -2), Vec3(10, 10, -2), Vec3(-10, 10, -2)),
      quad("occluder", Vec3(-10, 1.6 - 3, -1.5), Vec3(10, 1.6 + 3, -1.5), Vec3(10, 12, -1.5),
           Vec3(-10, 12, -1.5))};
  scene.camera.keys = {CameraKey{}};
  scene.camera.keys[0].fov_y_degrees = 90;
  Light sun;
  sun.kind = Light::Kind::directional;
  sun.direction = Vec3(0, -2, -1).normalized();
  scene.lights = {sun};
  scene.validate("wall-with-shadow-edge");
  return scene;
}

/// The share of `square` where v >= v0 + slope u: the square clipped by the half-plane.
double shadowed_share(const PixelSquare& s, double v0, double slope) {
  std::vector<Vec2> in = {Vec2(s.x0, s.y0), Vec2(s.x1, s.y0), Vec2(s.x1, s.y1), Vec2(s.x0, s.y1)},
                    out;
  auto f = [&](const Vec2& p) { return p.y() - v0 - slope * p.x(); };
  for (size_t k = 0; k < in.size(); ++k) {
    const Vec2 &p = in[k], &q = in[(k + 1) % in.size()];
    if (f(p) >= 0) out.push_back(p);
    if ((f(p) > 0 && f(q) < 0) || (f(p) < 0 && f(q) > 0))
      out.push_back(p + (q - p) * (f(p) / (f(p) - f(q))));
  }
  double twice = 0;
  for (size_t k = 0; k < out.size(); ++k) {
    const Vec2 &p = out[k], &q = out[(k + 1) % out.size()];
    twice += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice / s.area();
}

/// The largest relative error of the pixels that see the wall only, against the area-weighted
/// mix of the lit and shadowed colours; `crossed` counts those the edge crosses.
double worst_relative_error(const std::vector<Color>& colours, int* crossed) {
  const PixelRays image{kSize, kSize};
  const Color base = Material{}.base_color;
  // The wall's normal (0, 0, 1) against the unit vector towards the light, (0, 2, 1) / sqrt 5.
  const double cosine = 1 / std::sqrt(5.0);
  double worst = 0;
  *crossed = 0;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      const PixelSquare s = pixel_square(image, i, j);
      if (shadowed_share(s, kOccluderV0, kShadowSlope) > 0) continue;  // the occluder is seen
      const double shadowed = shadowed_share(s, kShadowV0, kShadowSlope);
      if (shadowed > 0.02 && shadowed < 0.98) ++*crossed;
      for (int c = 0; c < 3; ++c) {
        const double expected = base[c] * (kAmbient + kDiffuse * cosine * (1 - shadowed));
        const double got = colours[size_t(j * kSize + i)][c];
        worst = std::max(worst, std::abs(got - expected) / expected);
      }
    }
  return worst;
}

/// The exact frame of `scene` at t, each pixel's triangles by brute force, lit through a
/// brute-force shadow tracer, with `config`.
std::vector<Color> exact_lit_colours(const CameraSpaceScene& scene, double t,
                                     const ExactPixels::Config& config) {
  BruteForceShadowTracer tracer(scene);
  tracer.advance_to(t);
  const std::vector<CameraSpaceLight> lights = CameraSpaceLights(*scene.scene).at(t);
  const ExactLights lit{&lights, &tracer};
  const test::SceneTriangles triangles = test::scene_triangles(scene, t);
  const PixelRays image{kSize, kSize};
  ExactPixels pixels(scene, image, t, config, &lit);
  std::vector<Color> out;
  for (int j = 0; j < kSize; ++j)
    for (int i = 0; i < kSize; ++i) {
      std::vector<TriangleRef> set;
      for (size_t k : test::overlapping(triangles, pixel_square(image, i, j)))
        set.push_back(triangles.refs[k]);
      out.push_back(pixels.colour(i, j, set));
    }
  EXPECT_GT(pixels.stats().shadow_cuts, 0u);
  return out;
}

// The kinetic backend's --aa exact frame (its per-square sets, its kinetic AABB tree's shadow
// rays) and the brute-force read-out are the analytic mix within 2e-4 relative (measured 7.6e-5:
// the chord's ends are found within 2^-8 of a sub-triangle's edge); without the
// boundary's resolution (no halving, no bisection: the seven nodes' masks stand for the fan
// triangle) the edge pixels are off by far more, so the test sees the resolution.
TEST(ExactShadows, ShadowEdgeThroughPixelsIsTheAreaWeightedMix) {
  const Scene scene = wall_with_shadow_edge();
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  BackendConfig config;
  config.width = config.height = kSize;
  config.threads = 2;
  config.aa = Antialiasing::exact;
  std::unique_ptr<Backend> kinetic = make_backend("kinetic", cs, config);
  Frame frame;
  kinetic->render_antialiased(0.0, frame);
  int crossed = 0;
  const double kinetic_error = worst_relative_error(frame.color, &crossed);
  EXPECT_GE(crossed, 12);  // the edge runs across the image
  const double brute_error = worst_relative_error(exact_lit_colours(cs, 0.0, {}), &crossed);
  ExactPixels::Config unresolved;
  unresolved.shadow_area = 1;
  unresolved.shadow_bisections = 0;
  const double unresolved_error =
      worst_relative_error(exact_lit_colours(cs, 0.0, unresolved), &crossed);
  std::printf("worst relative error: kinetic %.3g, brute force %.3g, unresolved %.3g\n",
              kinetic_error, brute_error, unresolved_error);
  EXPECT_LT(kinetic_error, 2e-4);
  EXPECT_LT(brute_error, 2e-4);
  EXPECT_GT(unresolved_error, 1e-2);
  // The light mask AOV is the centre ray's: lit below the edge, shadowed above it.
  const PixelRays image{kSize, kSize};
  const int i = kSize / 2;
  const int below = int(std::floor((1 - (kShadowV0 - 0.2)) * kSize / 2));
  const int above = int(std::floor((1 - (kShadowV0 + 0.45)) * kSize / 2));
  EXPECT_EQ(frame.lit[frame.index(i, below)], 1u) << image.y(below);
  EXPECT_EQ(frame.lit[frame.index(i, above)], 0u) << image.y(above);
}

// A lit built-in with a point and a directional light (curved shadow boundaries, terminators,
// self-shadowing waves): the kinetic --aa exact frame against Embree's lit supersampling. What
// is left must be the reference's noise: below the diff's tolerance at 4096 samples, and falling
// from the 1024-sample reference to the 4096-sample one as the noise does (by about 2.8).
TEST(ExactShadows, LitWavySphereAgreesWithEmbreeWithinItsNoise) {
  RenderParams params;
  params.scene = "wavy-sphere:triangles=2000";
  params.width = params.height = test::kUnderAddressSanitizer ? 24 : 32;
  params.frames = 1;
  params.time = std::pair(0.5, 0.6);
  params.threads = 2;
  params.lights = {parse_light_flag("point:2,3,4"), parse_light_flag("dir:-1,1,1")};
  params.aa = Antialiasing::exact;
  RenderJob job(params);
  std::unique_ptr<Backend> kinetic = job.make_backend("kinetic");
  Frame exact;
  job.render_frame(*kinetic, 0, exact);
  auto embree_at = [&](int samples) {
    BackendConfig config = backend_config(params);
    config.aa = Antialiasing::none;
    config.aa_samples = samples;
    std::unique_ptr<Backend> embree = make_backend("embree", job.camera_space(), config);
    Frame frame;
    embree->render_supersampled(job.frame_times()[0], frame);
    return frame;
  };
  const Frame fine = embree_at(4096), coarse = embree_at(1024);
  const test::ImageError error = test::image_error(exact.color, fine.color);
  const test::ImageError coarse_error = test::image_error(exact.color, coarse.color);
  std::printf("exact vs embree 4096: rmse %.3g max %.3g; vs 1024: rmse %.3g max %.3g\n", error.rmse,
              error.max, coarse_error.rmse, coarse_error.max);
  EXPECT_LT(error.rmse, 1 / std::pow(64.0, 1.5));
  EXPECT_LT(error.max, 3.0 / 64);
  EXPECT_GT(coarse_error.rmse, 1.8 * error.rmse);
  EXPECT_EQ(exact.lit, fine.lit);  // both the centre rays' masks
  // Shadows are there: the lit frame is not the headlight's.
  RenderParams unlit = params;
  unlit.lights.clear();
  RenderJob unlit_job(unlit);
  std::unique_ptr<Backend> unlit_kinetic = unlit_job.make_backend("kinetic");
  Frame headlight;
  unlit_job.render_frame(*unlit_kinetic, 0, headlight);
  EXPECT_GT(test::image_error(headlight.color, exact.color).rmse, 1e-2);
}

}  // namespace
}  // namespace kinray

namespace kinray {
namespace {

/// The lit exact frame of `scene` at t read out with `config`, each pixel's triangles by brute
/// force; its counters added to `stats`.
std::vector<Color> lit_frame(const CameraSpaceScene& scene, int width, int height, double t,
                             const ExactPixels::Config& config, ExactPixels::Stats& stats) {
  const std::unique_ptr<ShadowTracer> tracer =
      make_kinetic_shadow_tracer(scene, ShadowTree::aabb, false);
  tracer->advance_to(t);
  const std::vector<CameraSpaceLight> lights = CameraSpaceLights(*scene.scene).at(t);
  const ExactLights lit{&lights, tracer.get()};
  const test::SceneTriangles triangles = test::scene_triangles(scene, t);
  const PixelRays image{width, height};
  ExactPixels pixels(scene, image, t, config, &lit);
  std::vector<Color> out;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) {
      std::vector<TriangleRef> set;
      for (size_t k : test::overlapping(triangles, pixel_square(image, i, j)))
        set.push_back(triangles.refs[k]);
      out.push_back(pixels.colour(i, j, set));
    }
  stats += pixels.stats();
  return out;
}

// The default resolution of shadow boundaries and kinks against a much deeper one (sub-triangles
// of 1/4096 of the pixel, 20 bisections, 5 kink halvings) on a lit built-in: curved shadows of
// the waves on the sphere itself, terminators, two lights. The shadow_area bound leaves a curved
// boundary's sagitta in each last sub-triangle: measured at 32 x 24, RMSE 4.3e-6 and worst pixel
// 1.1e-4 (a twentieth and a fifteenth of the 4096-sample reference's own noise), about 500
// shadow rays per pixel; the error falls about fourfold per fourfold smaller area. Without any
// resolution the nodes' masks stand for the boundary and the frame is ten times as far off.
TEST(ExactShadows, DefaultResolutionIsCloseToADeepOne) {
  Scene scene = make_builtin_scene("wavy-sphere", {{"triangles", 2000}});
  scene.lights = {parse_light_flag("point:2,3,4"), parse_light_flag("dir:-1,1,1")};
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const int width = test::kUnderAddressSanitizer ? 16 : 32;  // the deep frame: 3 s in Release
  const int height = test::kUnderAddressSanitizer ? 12 : 24;
  const double t = 0.5;
  ExactPixels::Config deep;
  deep.shadow_area = 1.0 / 4096;
  deep.shadow_bisections = 20;
  deep.kink_depth = 5;
  ExactPixels::Stats deep_stats, stats, none_stats;
  const std::vector<Color> reference = lit_frame(cs, width, height, t, deep, deep_stats);
  const test::ImageError error =
      test::image_error(lit_frame(cs, width, height, t, ExactPixels::Config{}, stats), reference);
  ExactPixels::Config none;
  none.shadow_area = 1;
  none.shadow_bisections = none.kink_depth = 0;
  const test::ImageError unresolved =
      test::image_error(lit_frame(cs, width, height, t, none, none_stats), reference);
  std::printf(
      "default vs deep: rmse %.3g max %.3g (%.0f shadow rays, %.1f cuts per pixel); unresolved: "
      "rmse %.3g max %.3g\n",
      error.rmse, error.max, double(stats.shadow_rays) / double(stats.pixels),
      double(stats.shadow_cuts) / double(stats.pixels), unresolved.rmse, unresolved.max);
  EXPECT_LT(error.rmse, 2e-5);
  EXPECT_LT(error.max, 1e-3);
  // At 16 x 12 (AddressSanitizer) each pixel holds four times the area and more of its boundary
  // is a curve's sagitta, which the default leaves too: measured 1.8x there, 14x at 32 x 24. The
  // frames are deterministic, so the margins are exact ones.
  EXPECT_GT(unresolved.rmse, (test::kUnderAddressSanitizer ? 1.5 : 3) * error.rmse);
  EXPECT_GT(stats.shadow_cuts, 0u);
}

}  // namespace
}  // namespace kinray
