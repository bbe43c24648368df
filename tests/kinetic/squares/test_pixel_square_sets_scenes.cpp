// The per-square sets on the built-in scenes with the audit on (every certificate and every
// pixel's set against brute force at random times), and the centre sample: every triangle that
// the brute force or the kinetic grid finds on a pixel's centre ray is in its square's set.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "kinetic/grid/frustum_grid.h"
#include "kinetic/squares/pixel_square_sets.h"
#include "renderer/backends/kinetic_backend.h"
#include "scenes/camera_space.h"
#include "scenes/scene_loader.h"
#include "tests/kinetic/squares/square_test_scenes.h"

namespace kinray {
namespace {

using test::expect_centre_hits_held;
using test::random_times;
using test::synthetic_scene;
using test::TestScene;

class PixelSquareSetsBuiltIn : public ::testing::TestWithParam<const char*> {};

INSTANTIATE_TEST_SUITE_P(PixelSquareSets, PixelSquareSetsBuiltIn,
                         ::testing::Values("wavy-sphere:triangles=300", "orbit:triangles=400",
                                           "crossing:triangles=300", "flythrough:triangles=300",
                                           "cloth:triangles=300", "static-moving:triangles=300"),
                         [](const auto& param) {
                           std::string name = param.param;
                           name = name.substr(0, name.find(':'));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST_P(PixelSquareSetsBuiltIn, MatchesBruteForceWithTheAuditOn) {
  const Scene scene = load_scene(GetParam());
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  const double t0 = scene.time_begin, t1 = scene.time_end;
  PixelSquareSets sets(kinetic_grid_input(cs, 48, 36), t0, {.audit = true});
  FrustumGrid grid(kinetic_grid_input(cs, 48, 36), t0);
  for (double t : random_times(t0, t1, 8, 3)) {
    ASSERT_NO_THROW(sets.advance_to(t));
    grid.advance_to(t);
    expect_centre_hits_held(sets);
    // The kinetic grid's front triangle of each pixel is in that pixel's square set.
    for (int j = 0; j < 36; ++j)
      for (int i = 0; i < 48; ++i) {
        const std::optional<GridHit> front = grid.front(i, j);
        if (!front) continue;
        const auto set = sets.triangles(i, j);
        EXPECT_NE(std::find(set.begin(), set.end(), SquareTriangle{front->mesh, front->triangle}),
                  set.end())
            << "front of (" << i << ", " << j << ") at t = " << t;
      }
  }
  EXPECT_GT(sets.stats().events.total(), 0u);
}

TEST(PixelSquareSets, CentreSampleTrianglesAreInTheSquareSets) {
  const TestScene scene = synthetic_scene();
  PixelSquareSets sets(scene.input(), -0.25);
  for (double t : random_times(-0.25, 2.3, 40, 13)) {
    sets.advance_to(t);
    expect_centre_hits_held(sets);
  }
}

}  // namespace
}  // namespace kinray
