// Exact antialiasing under the shutter (renderer/antialiasing/exact_shutter.h): the space-time box
// filter against its analytic value for an edge sweeping across pixels at constant speed, against
// Embree's samples in (x, y, t) on built-in scenes within their noise; the sampling peer's one
// sample is the centre ray's motion blur; the ids and depths stay the centre ray's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "kinetic/squares/pixel_square_sets.h"
#include "renderer/antialiasing/exact_shutter.h"
#include "renderer/backends/kinetic_backend.h"
#include "renderer/job/render_job.h"
#include "renderer/shading.h"
#include "tests/address_sanitizer.h"
#include "tests/renderer/analytic_scenes.h"
#include "tests/renderer/antialiasing/brute_force_squares.h"

namespace kinray {
namespace {

/// A triangle at depth 2 whose right edge is the vertical image line x = e(t) = -0.25 + t, every
/// other part of it far outside the image: it covers x < e(t) and slides right at one image unit
/// per second (a 90 degree, 8 x 8 image: 4 pixels per unit).
Scene sweeping_edge_scene() {
  constexpr double z = 2;
  auto at = [&](double t) {
    const double e = -0.25 + t;
    return std::vector<Vec3>{{e * z, -40 * z, z}, {e * z, 40 * z, z}, {(e - 80) * z, 0, z}};
  };
  return test::analytic_scene(
      {test::camera_space_object("edge", {Triangle{0, 1, 2}}, {at(0), at(1)}, {0.0, 1.0})});
}

/// Gauss-Legendre integral of f over [a, b] in `pieces` equal pieces of 16 nodes.
template <class F>
double integrate(double a, double b, int pieces, F&& f) {
  static const GaussLegendre rule = gauss_legendre(16);
  double sum = 0;
  const double h = (b - a) / pieces;
  for (int k = 0; k < pieces; ++k)
    for (size_t n = 0; n < rule.nodes.size(); ++n)
      sum += rule.weights[n] * h / 2 * f(a + h * (k + 0.5) + h / 2 * rule.nodes[n]);
  return sum;
}

/// The analytic space-time colour of pixel (i, j) under the sweeping edge over `window`: the edge
/// passes image x during the window's last tau(x) = (e(close) - x) / (e(close) - e(open)) of it
/// (clamped to [0, 1]), so C = B + mean over the square of (S(x, y) - B) tau(x), S the headlight
/// colour of the flat triangle along (x, y, 1), which does not depend on where the triangle is.
/// The square integral is taken by a fine product rule split at the kinks of tau.
Color analytic_colour(const CameraSpaceScene& cs, const PixelRays& image, int i, int j,
                      const ShutterWindow& window) {
  const double e0 = -0.25 + window.open, e1 = -0.25 + window.close;
  auto tau = [&](double x) { return std::clamp((e1 - x) / (e1 - e0), 0.0, 1.0); };
  const TriangleAtInstant triangle =
      triangle_at_instant(cs, 0, 0, shading_instant(cs, 0, window.time));
  const PixelSquare s = pixel_square(image, i, j);
  std::vector<double> cuts = {s.x0};
  for (double k : {e0, e1})
    if (k > s.x0 && k < s.x1) cuts.push_back(k);
  cuts.push_back(s.x1);
  std::sort(cuts.begin(), cuts.end());
  Color out;
  for (int c = 0; c < 3; ++c) {
    double sum = 0;
    for (size_t k = 0; k + 1 < cuts.size(); ++k)
      sum += integrate(cuts[k], cuts[k + 1], 4, [&](double x) {
        return integrate(s.y0, s.y1, 4, [&](double y) {
          const Vec3 d(x, y, 1);
          const double shade =
              headlight_color(triangle, d, view_direction(d, triangle.tan_half_fov))[c];
          return kBackgroundColor[c] + (shade - kBackgroundColor[c]) * tau(x);
        });
      });
    out[c] = float(sum / s.area());
  }
  return out;
}

/// The space-time frame of `window` by ExactShutter at `order`, each pixel's window cut at its
/// events or not, the sets built from `cs`.
Frame exact_shutter_frame(const CameraSpaceScene& cs, int size, const ShutterWindow& window,
                          int order, bool cut_at_events = true) {
  ExactShutter shutter(cs, {.order = order, .cut_at_events = cut_at_events}, 2, [&](double t) {
    PixelSquareSets::Config config;
    config.audit = true;
    return std::make_unique<PixelSquareSets>(kinetic_grid_input(cs, size, size), t, config);
  });
  Frame frame;
  frame.resize(size, size);
  shutter.render(window, frame);
  return frame;
}

// The known answer: the edge crosses pixel column 4 in the window's first half and column 5 in
// its second, so each of their space-time integrals has a kink at the window's middle, between
// nodes. Cut at its events (the triangle enters column 5's sets then, and column 4 holds it), each
// pixel's two parts are smooth and take two nodes each: measured 2.3e-6 off, that rule's error on
// the shading's curvature, where one fixed Gauss-Legendre rule over
// the window integrates the kink with an error that falls as 1 / n^2: for this ramp the mean is
// off by at most 1.1% of the contrast at n = 4 (the rule's nodes on a ramp that stops at the
// middle), at n = 16 by 1/16 of that. Columns the edge never enters or always covers are exact.
TEST(ExactShutter, SweepingEdgeMatchesTheAnalyticSpaceTimeMean) {
  const Scene scene = sweeping_edge_scene();
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  constexpr int kSize = 8;
  const PixelRays image{kSize, kSize};
  const ShutterWindow window{0.25, 0.5, 0.75};
  // The worst error of the swept columns 4 and 5: cut at events, then one rule at n = 4 and 16.
  double worst[3] = {0, 0, 0};
  const int orders[3] = {4, 4, 16};
  for (int o = 0; o < 3; ++o) {
    const Frame frame = exact_shutter_frame(cs, kSize, window, orders[o], o == 0);
    for (int j = 2; j < 6; ++j)
      for (int i = 2; i < 8; ++i) {
        const Color expected = analytic_colour(cs, image, i, j, window);
        const double error = (frame.color[frame.index(i, j)] - expected).cwiseAbs().maxCoeff();
        if (i == 4 || i == 5)
          worst[o] = std::max(worst[o], error);
        else
          EXPECT_LT(error, 2e-6) << "pixel " << i << ", " << j << " order " << orders[o];
      }
  }
  std::printf(
      "sweeping edge: worst error cut at events %.3g; one rule at order 4 %.3g, at "
      "order 16 %.3g\n",
      worst[0], worst[1], worst[2]);
  EXPECT_LT(worst[0], 1e-5);
  EXPECT_LT(worst[1], 0.011);
  EXPECT_LT(worst[2], 0.011 / 12);
  EXPECT_GT(worst[1], 8 * worst[2]);  // converging as a kink does, not stuck
}

RenderParams blurred_params(const std::string& scene, int size, const std::string& backend) {
  RenderParams params;
  params.scene = scene;
  params.backend = backend;
  params.width = params.height = size;
  params.frames = 2;
  params.threads = 2;
  params.shutter.shutter = 0.5;
  return params;
}

/// Frame `index` of `params` rendered through the job (its window under the shutter).
Frame job_frame(const RenderParams& params, size_t index) {
  RenderJob job(params);
  std::unique_ptr<Backend> backend = job.make_backend();
  Frame frame;
  for (size_t f = 0; f <= index; ++f) job.render_frame(*backend, f, frame);
  return frame;
}

// The space-time box filter against Embree's (x, y, t) samples: their difference must be the
// samples' noise. Embree at 1024 samples is sqrt(RMSE_1024^2 + RMSE_4096^2) from Embree at 4096,
// which bounds the 4096 reference's own noise; the exact frame must be within that of the 4096
// reference (plus 3e-5 for float vertices and colours), and its largest pixel error within the
// largest between the two sampled frames. The frame at the frame time without the shutter is far
// off the reference: the test sees the blur.
void expect_within_noise(const std::string& scene) {
  const int size = test::kUnderAddressSanitizer ? 16 : 32;
  RenderParams exact = blurred_params(scene, size, "kinetic");
  exact.aa = Antialiasing::exact;
  RenderParams sharp = exact;
  sharp.shutter.shutter = 0;
  RenderParams fine = blurred_params(scene, size, "embree");
  fine.aa_samples = 4096;
  RenderParams coarse = fine;
  coarse.aa_samples = 1024;
  const Frame e = job_frame(exact, 1), reference = job_frame(fine, 1), other = job_frame(coarse, 1),
              still = job_frame(sharp, 1);
  const test::ImageError between = test::image_error(other.color, reference.color);
  const test::ImageError error = test::image_error(e.color, reference.color);
  const test::ImageError unblurred = test::image_error(still.color, reference.color);
  std::printf(
      "%s: exact vs 4096: rmse %.3g max %.3g; 1024 vs 4096: rmse %.3g max %.3g; "
      "unblurred: rmse %.3g\n",
      scene.c_str(), error.rmse, error.max, between.rmse, between.max, unblurred.rmse);
  EXPECT_LT(error.rmse, between.rmse + 3e-5);
  EXPECT_LT(error.max, between.max + 2e-5);
  EXPECT_GT(unblurred.rmse, 3 * (between.rmse + 3e-5));
  // The AOVs are the centre ray's at the frame time, as --aa exact has them.
  EXPECT_EQ(e.object, still.object);
  EXPECT_EQ(e.prim, still.prim);
  EXPECT_EQ(e.depth, still.depth);
}

TEST(ExactShutter, WavySphereAgreesWithSpaceTimeSamples) {
  expect_within_noise("wavy-sphere:triangles=2000");
}

TEST(ExactShutter, OrbitAgreesWithSpaceTimeSamples) {
  expect_within_noise("orbit:triangles=1500");
}

// One antialiasing sample is the centre ray: --aa-samples 1 --shutter S is --shutter S bit for bit
// (time samples at the centre), and more samples spread over the square and blur the edges.
TEST(ExactShutter, OneSpaceTimeSampleIsTheCentreRaysMotionBlur) {
  RenderParams params = blurred_params("orbit:triangles=600", 16, "embree");
  const Frame blurred = job_frame(params, 1);
  params.aa_samples = 1;
  const Frame one = job_frame(params, 1);
  ASSERT_EQ(one.color.size(), blurred.color.size());
  EXPECT_EQ(std::memcmp(one.color.data(), blurred.color.data(), one.color.size() * sizeof(Color)),
            0);
  params.aa_samples = 16;
  const Frame sixteen = job_frame(params, 1);
  EXPECT_GT(test::image_error(sixteen.color, blurred.color).max, 0.01);
  EXPECT_EQ(sixteen.object, blurred.object);
}

// Overlapping windows (an irregular schedule): a window that opens before the sets' time builds
// them again and renders what a fresh filter renders, bit for bit.
TEST(ExactShutter, AWindowOpeningEarlierRebuildsTheSets) {
  const Scene scene = sweeping_edge_scene();
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const auto make = [&](double t) {
    return std::make_unique<PixelSquareSets>(kinetic_grid_input(cs, 8, 8), t);
  };
  ExactShutter shutter(cs, {}, 2, make);
  Frame first, second;
  first.resize(8, 8);
  second.resize(8, 8);
  shutter.render({0.4, 0.5, 0.6}, first);
  shutter.render({0.3, 0.4, 0.5}, second);
  EXPECT_EQ(shutter.stats().rebuilds, 1u);
  ExactShutter fresh(cs, {}, 2, make);
  Frame expected;
  expected.resize(8, 8);
  fresh.render({0.3, 0.4, 0.5}, expected);
  EXPECT_EQ(std::memcmp(second.color.data(), expected.color.data(),
                        expected.color.size() * sizeof(Color)),
            0);
  EXPECT_GT(test::image_error(first.color, second.color).max, 0.01);  // the edge moved
}

// Nothing moves in a window of length zero nor in a static scene's: each pixel is the exact
// frame's colour (one read-out at the frame time).
TEST(ExactShutter, AStillWindowIsTheExactFrame) {
  const Scene scene = sweeping_edge_scene();
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const Frame zero = exact_shutter_frame(cs, 8, {0.5, 0.5, 0.5}, 4);
  const std::vector<Color> exact =
      test::brute_force_exact_colours(cs, 8, 8, 0.5, test::scene_triangles(cs, 0.5));
  EXPECT_LT(test::image_error(zero.color, exact).max, 1e-6);
  // A static triangle in a window of length 0.5: every pixel is read once, at the frame time.
  const double z = 2;
  const Scene still = test::analytic_scene({test::camera_space_object(
      "still", {Triangle{0, 1, 2}},
      {{{-0.3 * z, -0.6 * z, z}, {0.55 * z, 0.1 * z, z}, {-0.8 * z, 0.7 * z, z}}})});
  const CameraSpaceScene still_cs = CameraSpaceScene::build(still);
  const Frame window = exact_shutter_frame(still_cs, 8, {0.25, 0.5, 0.75}, 4);
  const std::vector<Color> still_exact =
      test::brute_force_exact_colours(still_cs, 8, 8, 0.5, test::scene_triangles(still_cs, 0.5));
  EXPECT_LT(test::image_error(window.color, still_exact).max, 1e-6);
  EXPECT_GT(test::image_error(window.color, std::vector<Color>(64, kBackgroundColor)).max, 0.1);
}

}  // namespace
}  // namespace kinray
