// Imported models through the Embree reference backend: one 64 x 64 frame of each of a few models
// at the start, middle and end of their shot, and the centre rays hit them.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <string>

#include "renderer/backends/backend.h"
#include "renderer/backends/embree_backend.h"
#include "renderer/frame.h"
#include "scenes/camera_space.h"
#include "scenes/model_import.h"
#include "tests/scenes/model_test_support.h"
#include "util/warning.h"

namespace kinray {
namespace {

class ModelRender : public ::testing::TestWithParam<std::filesystem::path> {};

// A model that is not there fails (Debian's assimp-testmodels is installed by tools/setup.sh),
// except one of the shared folder when that folder is not beside the clone: that is a visible skip.
TEST_P(ModelRender, EmbreeHitsTheModelAtTheStartMiddleAndEndOfItsShot) {
  const std::filesystem::path& path = GetParam();
  const bool shared = path.string().starts_with(testing::kSharedModels.string());
  if (shared && !std::filesystem::exists(testing::kSharedModels))
    GTEST_SKIP() << "the shared folder is not beside the clone: " << testing::kSharedModels;
  ASSERT_TRUE(std::filesystem::exists(path)) << path << " is missing";
  const ScopedWarningSink quiet([](const std::string&) {});
  const Scene scene = load_model(path.string());
  const CameraSpaceScene camera_space = CameraSpaceScene::build(scene);
  BackendConfig config;
  config.width = config.height = 64;
  config.threads = 2;
  auto backend = make_embree_backend(camera_space, config);
  for (double t : {scene.time_begin, 0.5 * (scene.time_begin + scene.time_end), scene.time_end}) {
    Frame frame;
    backend->render(t, frame);
    size_t hits = 0;
    for (uint32_t object : frame.object) hits += object != kNoHit;
    EXPECT_GT(hits, 0u) << path << " at t=" << t;
    EXPECT_LT(hits, frame.pixel_count()) << path << " at t=" << t << ": framing leaves a margin";
  }
}

INSTANTIATE_TEST_SUITE_P(
    SkinnedMorphedAndSkeletonModels, ModelRender,
    ::testing::Values(testing::kTestModels / "glTF2/simple_skin/simple_skin.gltf",
                      testing::kTestModels / "X/BCN_Epileptic.X",
                      testing::kTestModels / "BVH/01_01.bvh",
                      testing::kTestModels / "FBX/huesitos.fbx",  // the model's own camera
                      testing::kSharedModels /
                          "glTF2/AnimatedMorphSphere/glTF/AnimatedMorphSphere.gltf"),
    [](const ::testing::TestParamInfo<std::filesystem::path>& model) {
      std::string name = model.param.stem().string();
      for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      return name;
    });

}  // namespace
}  // namespace kinray
