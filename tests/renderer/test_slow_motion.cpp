// 10x slow motion (docs/design.md, "Bands and the frame loop": the cost of event processing depends
// only on the motion, never on how many frames are read out). Rendering --inbetweens 10K instead of
// --inbetweens K over the same shot processes the same events, kind for kind; its frames at the
// shared times are identical to the normal render's (object, prim, depth and colour); and its
// in-between frames agree with Embree (zero real mismatches). Checked on every built-in scene and
// an animated model through the library, and once through `kinray render` as a user runs it.
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "renderer/backends/backend.h"
#include "renderer/job/frame_schedule.h"
#include "renderer/output/image_io.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"
#include "scenes/model_import.h"
#include "scenes/procedural.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 80, kHeight = 60;

BackendConfig config() {
  BackendConfig c;
  c.width = kWidth;
  c.height = kHeight;
  c.threads = 2;
  return c;
}

/// Renders the slow-motion schedule `slow` (every `factor`-th time shared with `normal`, to the
/// bit) and the normal one with two kinetic backends, and checks the three claims.
void check_slow_motion(const CameraSpaceScene& cs, const std::vector<double>& normal, const std::vector<double>& slow,
                       size_t factor) {
  ASSERT_EQ(slow.size(), (normal.size() - 1) * factor + 1);
  for (size_t m = 0; m < normal.size(); ++m) ASSERT_EQ(slow[m * factor], normal[m]) << "shared time " << m;

  auto kinetic = make_backend("kinetic", cs, config());
  auto kinetic_slow = make_backend("kinetic", cs, config());
  auto embree = make_backend("embree", cs, config());
  FrameComparator comparator(cs);
  Frame a, b, e;
  size_t inbetweens = 0, covered = 0;
  for (size_t f = 0; f < slow.size(); ++f) {
    kinetic_slow->render(slow[f], b);
    if (f % factor == 0) {
      kinetic->render(slow[f], a);
      shade_frame(cs, a, 2);
      shade_frame(cs, b, 2);
      EXPECT_EQ(a.object, b.object) << "t = " << slow[f];
      EXPECT_EQ(a.prim, b.prim) << "t = " << slow[f];
      EXPECT_EQ(a.depth, b.depth) << "t = " << slow[f];
      EXPECT_EQ(a.color, b.color) << "t = " << slow[f];
      continue;
    }
    embree->render(slow[f], e);
    const FrameDiff diff = comparator.compare(b, e);
    EXPECT_EQ(diff.mismatch_real, 0u) << "in-between frame at t = " << slow[f];
    covered += size_t(std::count_if(b.object.begin(), b.object.end(), [](uint32_t o) { return o != kNoHit; }));
    ++inbetweens;
  }
  EXPECT_EQ(inbetweens, (normal.size() - 1) * (factor - 1));
  EXPECT_GT(covered, inbetweens * size_t(kWidth * kHeight) / 50) << "the scene is in view";

  nlohmann::json normal_stats, slow_stats;
  kinetic->write_stats(normal_stats);
  kinetic_slow->write_stats(slow_stats);
  EXPECT_EQ(normal_stats["events"], slow_stats["events"]) << "the same events, kind for kind";
  EXPECT_GT(normal_stats["events"]["total"].get<uint64_t>(), 100u);
  EXPECT_GT(normal_stats["events"]["swap"].get<uint64_t>() + normal_stats["events"]["boundary"].get<uint64_t>(), 0u);
}

class BuiltinSlowMotion : public ::testing::TestWithParam<std::string> {};

TEST_P(BuiltinSlowMotion, SameEventsSameSharedFramesInBetweensAgreeWithEmbree) {
  // Keys every 1/8 s: the key grid is dyadic, so --inbetweens 20 puts every 10th frame at exactly
  // the time of a frame of --inbetweens 2 (frame_times computes t_k + m (t_k+1 - t_k) / K).
  const Scene scene = make_builtin_scene(GetParam(), {{"triangles", 800}, {"duration", 0.5}, {"keyrate", 8}});
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  FrameScheduleParams normal, slow;
  normal.inbetweens = 2;
  slow.inbetweens = 20;
  check_slow_motion(cs, frame_times(scene.key_times(), normal), frame_times(scene.key_times(), slow), 10);
}

INSTANTIATE_TEST_SUITE_P(Scenes, BuiltinSlowMotion,
                         ::testing::Values("wavy-sphere", "cloth", "orbit", "flythrough", "static-moving"),
                         [](const ::testing::TestParamInfo<std::string>& param) {
                           std::string name = param.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(SlowMotion, SkinnedModelInTenfoldSlowMotion) {
  // A model's keys are not dyadic, so --inbetweens 10K could put a shared frame an ulp away from
  // the --inbetweens K one. The slow-motion schedule is built as RenderJob would be given it: the
  // normal frames with nine in-betweens inserted between consecutive ones, shared times kept to
  // the bit.
  const fs::path path = "/usr/share/assimp/models/X/Testwuson.X";
  if (!fs::exists(path)) GTEST_SKIP() << path << " is not installed";
  const Scene scene = load_model(path.string());
  const CameraSpaceScene cs = CameraSpaceScene::build(scene);
  FrameScheduleParams normal;
  normal.frames = 9;
  const std::vector<double> coarse = frame_times(scene.key_times(), normal);
  std::vector<double> fine;
  for (size_t m = 0; m + 1 < coarse.size(); ++m)
    for (int q = 0; q < 10; ++q) fine.push_back(q == 0 ? coarse[m] : coarse[m] + q * (coarse[m + 1] - coarse[m]) / 10);
  fine.push_back(coarse.back());
  check_slow_motion(cs, coarse, fine, 10);
}

int run(const std::string& args) {
  const int status = std::system((std::string(KINRAY_BINARY) + " " + args + " > /dev/null 2>&1").c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

std::string read_bytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

TEST(SlowMotion, RenderCommandInTenfoldSlowMotion) {
  const fs::path folder = fs::path(::testing::TempDir()) / "kinray_slow_motion";
  fs::remove_all(folder);
  const std::string common = " --backend kinetic --size 64x48 --aov id,depth --threads 2 -q";
  const std::string scene = "cloth:triangles=600,duration=0.5,keyrate=8";
  ASSERT_EQ(run("render " + scene + common + " --inbetweens 2 --out " + (folder / "normal").string() +
                " --stats " + (folder / "normal.json").string()),
            0);
  ASSERT_EQ(run("render " + scene + common + " --inbetweens 20 --out " + (folder / "slow").string() + " --stats " +
                (folder / "slow.json").string()),
            0);
  const nlohmann::json normal = read_json(folder / "normal.json"), slow = read_json(folder / "slow.json");
  ASSERT_EQ(normal["frames"], 9);
  ASSERT_EQ(slow["frames"], 81);
  EXPECT_EQ(normal["events"], slow["events"]) << "kinray render --stats: the same events, kind for kind";
  for (int m = 0; m < 9; ++m) {
    char a[64], b[64];
    for (const char* kind : {"frame_%05d.png", "id_%05d.png", "depth_%05d.tiff"}) {
      std::snprintf(a, sizeof a, kind, m);
      std::snprintf(b, sizeof b, kind, 10 * m);
      EXPECT_EQ(read_bytes(folder / "normal" / a), read_bytes(folder / "slow" / b)) << a << " vs slow " << b;
    }
  }
}

}  // namespace
}  // namespace kinray
