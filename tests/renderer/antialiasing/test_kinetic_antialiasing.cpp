// `--aa exact` end to end: the kinetic backend's frames, its per-square sets advanced from frame
// to frame with the audit on, read out as the exact read-out reads brute-force sets; the id and
// depth AOVs stay the centre ray's, those of the frame without antialiasing.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "renderer/job/render_job.h"
#include "tests/address_sanitizer.h"
#include "tests/renderer/antialiasing/brute_force_squares.h"
#include "util/input_error.h"

namespace kinray {
namespace {

TEST(KineticAntialiasing, FramesAreTheExactReadOutOfBruteForceSets) {
  for (const char* scene :
       {"wavy-sphere:triangles=2000", "orbit:triangles=1500", "flythrough:triangles=1500"}) {
    SCOPED_TRACE(scene);
    RenderParams params;
    params.scene = scene;
    params.width = 32;
    params.height = 24;
    params.frames = test::kUnderAddressSanitizer ? 2 : 4;  // audited: ten times slower there
    params.threads = 2;
    params.audit = true;  // the sets and the grid are audited at every frame
    params.aa = Antialiasing::exact;
    RenderJob job(params);
    std::unique_ptr<Backend> backend = job.make_backend("kinetic");
    RenderParams sharp_params = params;
    sharp_params.aa = Antialiasing::none;
    RenderJob sharp_job(sharp_params);
    std::unique_ptr<Backend> sharp = sharp_job.make_backend("kinetic");
    for (size_t f = 0; f < job.frame_times().size(); ++f) {
      Frame frame, centre;
      job.render_frame(*backend, f, frame);
      sharp_job.render_frame(*sharp, f, centre);
      const double t = job.frame_times()[f];
      const std::vector<Color> expected =
          test::brute_force_exact_colours(job.camera_space(), params.width, params.height, t,
                                          test::scene_triangles(job.camera_space(), t));
      const test::ImageError error = test::image_error(frame.color, expected);
      // The same read-out of the same visible regions: only the order of the sets' triangles
      // (and the superset's extra ones) can move the last bits.
      EXPECT_LT(error.max, 1e-6) << "frame " << f;
      EXPECT_EQ(frame.object, centre.object) << "frame " << f;
      EXPECT_EQ(frame.prim, centre.prim) << "frame " << f;
      EXPECT_EQ(frame.depth, centre.depth) << "frame " << f;
      // Antialiasing changes the colour of the pixels along silhouettes, not nowhere.
      const test::ImageError against_centre = test::image_error(frame.color, centre.color);
      EXPECT_GT(against_centre.max, 0.01) << "frame " << f;
    }
  }
}

TEST(KineticAntialiasing, WhatItDoesNotDoYetIsRefusedNamingTheFlag) {
  RenderParams params;
  params.scene = "wavy-sphere:triangles=400";
  params.width = params.height = 16;
  params.frames = 1;
  params.aa = Antialiasing::exact;
  const auto refusal = [](const RenderParams& p) -> std::string {
    try {
      RenderJob job(p);
      (void)job.make_backend();
    } catch (const InputError& e) {
      return e.where() + ": " + e.message();
    }
    return "(accepted)";
  };
  EXPECT_EQ(refusal(params), "(accepted)");
  RenderParams lit = params;
  lit.lights = {Light{}};
  EXPECT_EQ(refusal(lit), "(accepted)");  // lit: shadow rays at the quadrature nodes
  RenderParams blurred = params;
  blurred.shutter.shutter = 0.5;
  EXPECT_EQ(refusal(blurred), "(accepted)");  // the space-time box filter
  RenderParams blurred_lit = lit;
  blurred_lit.shutter.shutter = 0.5;
  EXPECT_EQ(
      refusal(blurred_lit)
          .rfind("aa: exact antialiasing under the shutter (--shutter) of a scene with lights", 0),
      0u);
  RenderParams sampled = params;
  sampled.aa_samples = 4;
  EXPECT_EQ(refusal(sampled).rfind("aa: exact antialiasing needs no samples", 0), 0u);
  RenderParams embree = params;
  embree.backend = "embree";
  EXPECT_EQ(refusal(embree).rfind("aa: the embree backend has no exact antialiasing", 0), 0u);
}

}  // namespace
}  // namespace kinray
