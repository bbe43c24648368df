// `kinray bench --structure aabb,boxtree`: what the table claims, on a small deforming scene.
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/tools/kinray_process.h"
#include "util/input_error.h"
#include "verification/tree_benchmark.h"

namespace kinray {
namespace {

TEST(TreeBenchmark, EventsPerIntervalDoNotDependOnInbetweens) {
  TreeBenchParams params;
  params.base.scene = "wavy-sphere:triangles=3000";
  params.base.width = params.base.height = 32;
  params.base.time = std::make_pair(0.0, 0.125);
  params.inbetweens = {1, 8};
  params.repetitions = 1;
  params.shadow_frames = 2;
  const TreeBenchReport report = run_tree_benchmark(params);
  ASSERT_EQ(report.points.size(), 4u);  // (aabb, boxtree) x (1, 8)
  const TreeBenchPoint &aabb1 = report.points[0], &box1 = report.points[1],
                       &aabb8 = report.points[2], &box8 = report.points[3];
  EXPECT_EQ(aabb1.tree, "aabb");
  EXPECT_EQ(box1.tree, "boxtree");
  EXPECT_EQ(aabb1.events_per_interval, aabb8.events_per_interval);  // the kinetic claim
  EXPECT_EQ(box1.events_per_interval, box8.events_per_interval);
  EXPECT_GT(aabb1.events_per_interval, 0);
  EXPECT_LT(box1.failures_per_interval, aabb1.failures_per_interval);
  EXPECT_DOUBLE_EQ(aabb8.bv_updates_per_interval,
                   8 * aabb1.bv_updates_per_interval);  // one pass per frame
  EXPECT_GT(aabb8.shadow_rays_per_frame, 100u);
  EXPECT_GT(aabb8.update_speedup, 0);
  const nlohmann::json json = report.to_json();
  for (const char* key : {"tree", "inbetweens", "triangles", "events_per_interval",
                          "bv_updates_per_interval", "kinetic_update_ms_per_frame",
                          "bottom_up_update_ms_per_frame", "update_speedup", "total_ms_per_frame"})
    EXPECT_TRUE(json["structure_points"][0].contains(key)) << key;
}

TEST(TreeBenchmark, UnknownStructureIsAnInputError) {
  EXPECT_THROW((void)parse_tree_structures("aabb,octree"), InputError);
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / "kinray_tree_bench_test";
  std::filesystem::create_directories(dir);
  const test::CommandRun run = test::run_kinray("bench wavy-sphere --structure octree", dir);
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("kinray: error: --structure: unknown structure 'octree'"),
            std::string::npos)
      << run.err;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kinray
