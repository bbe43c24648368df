// BART's kitchen and robots (../shared/data/bart) load whole: triangles (the sum of the
// `triangles N` counts over every included file), the animation range and BART's resolution, all
// read from the files themselves, the camera's keys, and the bounds the loader gave when the
// scene was first checked by eye; and the kinetic backend (audit on) agrees with Embree on a
// few frames (0 real mismatches). Sampled at 1 key per second to keep memory and time small.
#include <gtest/gtest.h>

#include <filesystem>

#include "renderer/backends/backend.h"
#include "renderer/job/memory_estimate.h"
#include "scenes/aff_scene.h"
#include "scenes/camera_space.h"
#include "tests/scenes/aff_file_facts.h"
#include "util/warning.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const fs::path kBart = fs::path(KINRAY_SHARED_DIR) / "data" / "bart";

struct BartScene {
  const char* file;
  Eigen::AlignedBox3d bounds;  ///< recorded: a regression check, not derived from the files
};

void check_scene(const BartScene& expected, bool audit) {
  const fs::path path = kBart / expected.file;
  if (!fs::exists(path)) GTEST_SKIP() << path << " is absent (../shared/data/bart)";
  // The missing texture and keyless transforms warn.
  const ScopedWarningSink quiet([](const std::string&) {});
  const Scene scene = load_aff(path, 1.0);
  scene.validate(path.string());
  EXPECT_EQ(scene.triangle_count(), test::aff_triangle_count(path));
  const std::vector<double> range = test::aff_numbers_after(path, "a", 3);  // start end frames
  const std::vector<double> resolution = test::aff_numbers_after(path, "resolution", 2);
  ASSERT_EQ(range.size(), 3u);
  ASSERT_EQ(resolution.size(), 2u);
  EXPECT_EQ(scene.time_begin, range[0]);
  EXPECT_EQ(scene.time_end, range[1]);
  EXPECT_EQ(scene.frame_count, int(range[2]));
  EXPECT_EQ(scene.image_width, int(resolution[0]));
  EXPECT_EQ(scene.image_height, int(resolution[1]));
  // --keyrate 1: a camera key every second from the start to the end.
  EXPECT_EQ(scene.camera.keys.size(), size_t(range[1] - range[0]) + 1);
  const Eigen::AlignedBox3d bounds = scene.bounds();
  EXPECT_TRUE(bounds.isApprox(expected.bounds, 1e-4))
      << bounds.min().transpose() << " / " << bounds.max().transpose();

  // Kinetic against Embree at three frames of a 48 x 36 image.
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  BackendConfig config;
  config.width = 48;
  config.height = 36;
  config.threads = 2;
  config.audit = audit;
  auto kinetic = make_backend("kinetic", cs, config);
  config.audit = false;
  auto embree = make_backend("embree", cs, config);
  FrameComparator comparator(cs);
  for (double t : {1.0, 1.25, 1.5}) {
    Frame a, b;
    kinetic->render(t, a);
    embree->render(t, b);
    const FrameDiff diff = comparator.compare(a, b);
    EXPECT_EQ(diff.mismatch_real, 0u) << expected.file << " at t=" << t;
    size_t hits = 0;
    for (uint32_t object : b.object) hits += object != kNoHit;
    EXPECT_GT(hits, b.pixel_count() / 2) << expected.file << " at t=" << t;
  }
}

TEST(BartScenes, Kitchen) {
  check_scene(
      {"kitchen/kitchen.aff", Eigen::AlignedBox3d(Vec3(-2, -1.1, -3.75), Vec3(6, 2.9, 4.33))},
      true);
}

TEST(BartScenes, Robots) {
  check_scene(
      {"robots/Robot.aff",
       Eigen::AlignedBox3d(Vec3(-164.148, -0.651981, -435.355), Vec3(164.148, 535.355, 250.097))},
      // Audited: at t = 1.4997 two nearly edge-on triangles sharing an edge have a depth
      // certificate whose products cancel below their rounding (kinetic/core/exact_certificate.h).
      true);
}

TEST(BartScenes, TheRobotsHoldTheirVerticesOnceAndAShortShotHoldsItsOwnKeys) {
  const fs::path path = kBart / "robots/Robot.aff";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is absent (../shared/data/bart)";
  const ScopedWarningSink quiet([](const std::string&) {});
  const Scene scene = load_aff(path);  // every key of the animation (800)
  const double vertices = double(scene.vertex_count());
  // Their parts move rigidly under BART's transforms: each vertex is held once, not per key.
  const SceneSize whole = size_of(scene);
  EXPECT_LT(whole.world_vertex_keys, 1.01 * vertices);
  EXPECT_GT(whole.camera_vertex_keys, 500 * vertices);
  // A shot of a tenth of a second holds the few keys around it in camera space, and the
  // estimate of a small render of it is far below a gigabyte.
  const std::pair<double, double> shot(1.0, 1.1);
  const SceneSize part = size_of(scene, shot);
  EXPECT_LT(part.camera_vertex_keys, whole.camera_vertex_keys / 50);
  EXPECT_LT(estimate_render_memory(part, 64, 48, "kinetic").total(), 1e9);
  const CameraSpaceScene cs = CameraSpaceScene::build(scene, shot);
  EXPECT_EQ(size_of(cs).camera_vertex_keys, part.camera_vertex_keys);
}

}  // namespace
}  // namespace kinray
