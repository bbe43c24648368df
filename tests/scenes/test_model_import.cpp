// Every animated model of Debian's assimp-testmodels (and of the shared folder) loads with the
// triangle count and shot that its file says, moves when its animation moves it, and is seen by
// its camera. The expected figures were read off the files, as the comments say; a BVH test
// re-derives its figures from the file's text.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/model_import.h"
#include "tests/scenes/model_test_support.h"
#include "util/input_error.h"
#include "util/warning.h"

namespace kinray {
namespace {

using testing::bounds_in_view;
using testing::fraction_in_view;
using testing::kSharedModels;
using testing::kTestModels;
using testing::largest_motion;

enum class Motion {
  moves,        ///< the animation moves vertices
  holds_still,  ///< the animation's keys are all equal (checked in the file): nothing moves
  camera_only,  ///< only the camera is animated, and assimp 5.2 misplaces 3DS/ASE cameras
  single_key,   ///< the animation has one key time: a still pose, shown for 1 s
};

struct AnimatedModel {
  const char* path;  ///< under kTestModels, or kSharedModels when `shared`
  const char* animation;
  size_t triangles;
  double first_key, last_key;  ///< the shot, in seconds
  Motion motion;
  bool own_camera = false;  ///< the model's own camera is kept (else automatic framing)
  bool shared = false;
};

// Tick rates: 3DS stores none (assimp's 0 -> 25 per second); ASE has 160 ticks per frame at 30 fps
// = 4800; LWS 30 fps; MDL and X state theirs; glTF and COLLADA come in milliseconds (1000). X files
// list each face twice (MeshFaces and MeshNormals), so the counts below are half the face lines.
const std::vector<AnimatedModel> kModels = {
    // 3DS: boxes of 12 triangles; keys in frames at 25 per second.
    {"3DS/CameraRollAnim.3ds", "", 12, 0, 120 / 25.0, Motion::camera_only},
    {"3DS/CameraRollAnimWithChildObject.3ds", "", 24, 0, 120 / 25.0,
     Motion::moves},  // child box rides the camera
    {"3DS/RotatingCube.3DS", "", 12, 0, 181 / 25.0, Motion::moves},
    {"3DS/TargetCameraAnim.3ds", "", 12, 0, 90 / 25.0, Motion::camera_only},
    // ASE: the same scenes exported from 3ds Max as text; keys in ticks of 1/4800 s.
    {"ASE/CameraRollAnim.ase", "", 12, 0, 19200 / 4800.0, Motion::camera_only},
    {"ASE/CameraRollAnimWithChildObject.ase", "", 24, 0, 19200 / 4800.0, Motion::moves},
    {"ASE/MotionCaptureROM.ase", "", 2016, 0, 216800 / 4800.0, Motion::moves},  // 26 limb meshes
    {"ASE/RotatingCube.ASE", "", 12, 0, 28800 / 4800.0, Motion::moves},
    {"ASE/TargetCameraAnim.ase", "", 12, 0, 14400 / 4800.0, Motion::camera_only},
    {"ASE/anim.ASE", "", 24, 0, 16000 / 4800.0, Motion::moves},
    {"ASE/anim2.ASE", "", 24, 0, 16000 / 4800.0, Motion::moves},
    // BVH: skeletons drawn by assimp's skeleton mesh (see BvhFiguresFollowFromTheFile); the shot
    // is (Frames - 1) * Frame Time.
    {"BVH/01_01.bvh", "", 164, 0, 2751 * 0.0083333, Motion::moves},
    {"BVH/01_03.bvh", "", 164, 0, 4510 * 0.0083333, Motion::moves},
    {"BVH/Boxing_Toes.bvh", "", 140, 0, 3068 * 0.01, Motion::moves},
    // CSM: 44 markers, each an octahedron (8 triangles); $FirstFrame 1 .. $LastFrame 2439 at $Rate
    // 120.
    {"CSM/ThomasFechten.csm", "", 44 * 8, 0, 2439 / 120.0, Motion::moves},
    // COLLADA: 64 cubes keyed at frames 1..359 of 30 fps; one cube keyed at frames 1..40 of 24 fps.
    {"Collada/anims_with_full_rotations_between_keys.DAE", "", 64 * 12, 1 / 30.0, 359 / 30.0,
     Motion::moves},
    {"Collada/box_nested_animation.dae", "", 12, 1 / 24.0, 40 / 24.0, Motion::moves},
    // FBX from Blender at 24 and 25 fps, each with the camera Blender exported.
    {"FBX/animation_with_skeleton.fbx", "", 2112, 0, 20 / 24.0, Motion::moves, true},
    {"FBX/huesitos.fbx", "", 120, 0, 39 / 25.0, Motion::moves, true},
    // LWS: a LightWave cube (12 triangles) moved by keys at 30 fps.
    {"LWS/move_x.lws", "", 12, 0, 40 / 30.0, Motion::moves},
    {"LWS/move_x_oldformat_56.lws", "", 12, -1.2 / 30, 0,
     Motion::holds_still},  // both keys at y = -0.04
    {"LWS/move_x_oldformat_6.lws", "", 12, 0, 40 / 30.0, Motion::moves},
    {"LWS/move_x_post_constant.lws", "", 12, 0, 39 / 30.0, Motion::moves},
    {"LWS/move_x_post_linear.lws", "", 12, 0, 39 / 30.0, Motion::moves},
    {"LWS/move_x_post_offset_repeat.lws", "", 12, 0, 39 / 30.0, Motion::moves},
    {"LWS/move_x_post_repeat.lws", "", 12, 0, 39 / 30.0, Motion::moves},
    {"LWS/move_x_post_reset.lws", "", 12, 0, 39 / 30.0, Motion::moves},
    {"LWS/move_xz_bezier.lws", "", 12, 0, 89 / 30.0, Motion::moves},
    {"LWS/move_xz_hermite.lws", "", 12, 0, 89 / 30.0, Motion::moves},
    {"LWS/move_xz_linear.lws", "", 12, 0, 89 / 30.0, Motion::moves},
    {"LWS/move_xz_spline.lws", "", 12, 0, 89 / 30.0, Motion::moves},
    {"LWS/move_xz_stepped.lws", "", 12, 0, 89 / 30.0, Motion::moves},
    // Its position keys are unsorted and repeat times (-21, 0): sorted, the last of each kept.
    {"LWS/move_y_pre_ofrep_post_osc.lws", "", 12, -72 / 30.0, 51 / 30.0, Motion::moves},
    // Half-Life 1 MDL: the "idle" sequences hold one pose (three equal keys at 25 or 30 fps).
    {"MDL/MDL (HL1)/alpha_test.mdl", "", 12, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/blend_additive.mdl", "", 2, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/chrome_sphere.mdl", "", 480, 0, 220 / 25.0, Motion::moves},
    {"MDL/MDL (HL1)/duplicate_bodyparts.mdl", "", 9, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/duplicate_sequence_groups/duplicate_sequence_groups.mdl", "", 1, 0, 2 / 25.0,
     Motion::holds_still},
    {"MDL/MDL (HL1)/duplicate_sequences.mdl", "", 1, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/duplicate_submodels.mdl", "", 6, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/man.mdl", "walk", 190, 0, 25 / 30.0, Motion::moves},
    {"MDL/MDL (HL1)/sequence_transitions.mdl", "", 1, 0, 2 / 30.0, Motion::holds_still},
    {"MDL/MDL (HL1)/unnamed_bodyparts.mdl", "", 9, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/unnamed_bones.mdl", "", 96, 0, 2 / 25.0, Motion::holds_still},
    {"MDL/MDL (HL1)/unnamed_sequence_groups/unnamed_sequence_groups.mdl", "", 1, 0, 2 / 25.0,
     Motion::holds_still},
    {"MDL/MDL (HL1)/unnamed_sequences.mdl", "", 1, 0, 2 / 25.0, Motion::holds_still},
    // SMD reference poses: an "animation" of one key.
    {"SMD/WusonSMD.smd", "", 3732, 0, 1, Motion::single_key},
    {"SMD/holy_grailref.smd", "", 896, 0, 1, Motion::single_key},
    {"SMD/triangle.smd", "", 1, 0, 1, Motion::single_key},
    // DirectX: AnimTicksPerSecond 4800 (BCN, Wuson) and 24 (anim_test, keys at frames 1..24).
    {"X/BCN_Epileptic.X", "", 5126, 0, 15840 / 4800.0, Motion::moves},
    {"X/Testwuson.X", "", 3732, 0, 4640 / 4800.0,
     Motion::moves},  // first of 3 animations: Wuson_Run
    {"X/anim_test.x", "", 840, 1 / 24.0, 24 / 24.0,
     Motion::moves},  // two of its four bones have no node
    // glTF 2: morph cube (127 keys over 4.2 s) and the two-bone skin of the glTF tutorial (0 .. 5.5
    // s).
    {"glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf", "", 12, 0, 4.2,
     Motion::moves},
    {"glTF2/simple_skin/simple_skin.gltf", "", 8, 0, 5.5, Motion::moves},
    // Shared: README.md lists 960 and 1 triangles; inputs run 0 .. 7.2 s (30 fps) and 0 .. 4 s.
    {"glTF2/AnimatedMorphSphere/glTF/AnimatedMorphSphere.gltf", "", 960, 0, 7.2, Motion::moves,
     false, true},
    {"glTF2/SimpleMorph/glTF/SimpleMorph.gltf", "", 1, 0, 4, Motion::moves, false, true},
};

void PrintTo(const AnimatedModel& model, std::ostream* out) {
  *out << model.path;
}

std::string test_name(const ::testing::TestParamInfo<AnimatedModel>& info) {
  std::string name = std::filesystem::path(info.param.path).stem().string() + "_" +
                     std::filesystem::path(info.param.path).extension().string().substr(1);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return name;
}

class AnimatedModels : public ::testing::TestWithParam<AnimatedModel> {};

TEST_P(AnimatedModels, LoadsWithItsTrianglesShotMotionAndCamera) {
  const AnimatedModel& model = GetParam();
  const std::filesystem::path path = (model.shared ? kSharedModels : kTestModels) / model.path;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  ModelOptions options;
  options.animation = model.animation;
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = load_model(path.string(), options);

  EXPECT_EQ(scene.triangle_count(), model.triangles);
  // glTF stores seconds as floats, which assimp turns into float milliseconds.
  const double tolerance = 1e-5 * std::max(1.0, std::abs(model.last_key));
  EXPECT_NEAR(scene.time_begin, model.first_key, tolerance);
  EXPECT_NEAR(scene.time_end, model.last_key, tolerance);

  const double size = scene.bounds().diagonal().norm();
  ASSERT_GT(size, 0);
  switch (model.motion) {
    case Motion::moves: {
      EXPECT_GT(largest_motion(scene), 1e-3 * size);
      // ... between two consecutive key times, not just somewhere along the shot.
      double step = 0;
      for (const Object& object : scene.objects)
        for (size_t k = 1; k < object.key_count(); ++k)
          for (uint32_t v = 0; v < object.vertex_count(); ++v)
            step = std::max(step,
                            (object.key_positions[k][v] - object.key_positions[k - 1][v]).norm());
      EXPECT_GT(step, 0.0);
      break;
    }
    case Motion::single_key:
      EXPECT_NE(warnings.find("single key time"), std::string::npos) << warnings;
      [[fallthrough]];
    case Motion::holds_still:
    case Motion::camera_only:
      EXPECT_EQ(largest_motion(scene), 0.0);
      for (const Object& object : scene.objects) EXPECT_EQ(object.key_count(), 1u);
      break;
  }

  if (model.own_camera) {
    EXPECT_EQ(warnings.find("framing it automatically"), std::string::npos) << warnings;
    EXPECT_GT(fraction_in_view(scene, scene.time_begin), 0.0);
    EXPECT_GT(fraction_in_view(scene, scene.time_end), 0.0);
  } else {
    // Automatic framing: what the frames show stays in view all shot long, keys or not.
    EXPECT_EQ(scene.camera_source.kind, CameraSource::Kind::automatic);
    for (double t :
         {scene.time_begin, 0.37 * scene.time_begin + 0.63 * scene.time_end, scene.time_end})
      EXPECT_DOUBLE_EQ(fraction_in_view(scene, t), 1.0) << t;
    if (scene.camera.keys.size() == 1) {
      EXPECT_TRUE(bounds_in_view(scene, scene.time_begin));
    }
  }
  EXPECT_NO_THROW(scene.validate(path.string()));
}

INSTANTIATE_TEST_SUITE_P(Model, AnimatedModels, ::testing::ValuesIn(kModels), test_name);

/// The figures of the BVH rows above, re-derived from the file's text: assimp draws a skeleton as
/// a four-sided pyramid per parent-child link of non-zero length and an octahedron per end site
/// (leaf), and the shot is (Frames - 1) * Frame Time.
TEST(ModelBvh, FiguresFollowFromTheFile) {
  for (const char* name : {"BVH/01_01.bvh", "BVH/01_03.bvh", "BVH/Boxing_Toes.bvh"}) {
    const std::filesystem::path path = kTestModels / name;
    if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
    std::ifstream file(path);
    std::string line;
    size_t links = 0, zero_links = 0, leaves = 0, frames = 0;
    double frame_time = 0;
    bool root_offset_seen = false;
    while (std::getline(file, line)) {
      std::istringstream words(line);
      std::string word;
      words >> word;
      if (word == "End") ++leaves;
      if (word == "OFFSET") {
        double x, y, z;
        words >> x >> y >> z;
        if (!root_offset_seen) {
          root_offset_seen = true;  // the root's offset places it, it links to no parent
          continue;
        }
        ++links;
        if (x == 0 && y == 0 && z == 0) ++zero_links;
      }
      if (word == "Frames:") words >> frames;
      if (word == "Frame") {
        words >> word >> frame_time;  // "Frame Time: t"
      }
    }
    const Scene scene = load_model(path.string());
    EXPECT_EQ(scene.triangle_count(), 4 * (links - zero_links) + 8 * leaves) << name;
    // assimp keeps 1 / Frame Time as its tick rate in single precision.
    EXPECT_NEAR(scene.time_end - scene.time_begin, double(frames - 1) * frame_time,
                1e-6 * frames * frame_time)
        << name;
    EXPECT_EQ(scene.objects.at(0).key_count(), frames) << name;
  }
}

/// MD5 animations live beside the mesh (name.md5anim). Debian ships SimpleCube.md5mesh alone, so
/// the test writes a three-frame animation at 24 fps that turns joint1 from the bind pose.
TEST(ModelMd5, MeshWithItsAnimationFileMoves) {
  const std::filesystem::path mesh = kTestModels / "MD5/SimpleCube.md5mesh";
  if (!std::filesystem::exists(mesh)) GTEST_SKIP() << mesh << " is not installed";
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("kinray_model_md5_" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  std::filesystem::copy_file(mesh, directory / "SimpleCube.md5mesh",
                             std::filesystem::copy_options::overwrite_existing);
  std::ofstream(directory / "SimpleCube.md5anim") << R"(MD5Version 10
commandline ""

numFrames 3
numJoints 3
frameRate 24
numAnimatedComponents 3

hierarchy {
	"origin"	-1 0 0
	"root"	0 0 0
	"joint1"	1 56 0
}

bounds {
	( -64 -64 -64 ) ( 64 64 64 )
	( -64 -64 -64 ) ( 64 64 64 )
	( -64 -64 -64 ) ( 64 64 64 )
}

baseframe {
	( 0 0 0 ) ( 0 0 0 )
	( 0 0 0 ) ( -0.5001951456 0.4998047054 -0.4998047054 )
	( 0.0249728262 0.0000019062 31.9803333282 ) ( -0.7071067691 0.0000000527 0.0000000105 )
}

frame 0 {
	-0.7071067691 0.0000000527 0.0000000105
}

frame 1 {
	-0.3826834324 0 0
}

frame 2 {
	0 0 0
}
)";
  const Scene scene = load_model((directory / "SimpleCube.md5mesh").string());
  std::filesystem::remove_all(directory);
  EXPECT_EQ(scene.triangle_count(), 12u);
  EXPECT_DOUBLE_EQ(scene.time_begin, 0);
  EXPECT_NEAR(scene.time_end, 2 / 24.0, 1e-12);  // frames 0, 1, 2 at 24 fps
  EXPECT_EQ(scene.objects.at(0).key_count(), 3u);
  EXPECT_GT(largest_motion(scene), 1e-3 * scene.bounds().diagonal().norm());
  EXPECT_TRUE(bounds_in_view(scene, scene.time_begin));
}

TEST(ModelAnimationChoice, ByNameOrIndexAndUnknownListsTheAvailableOnes) {
  const std::filesystem::path path = kTestModels / "X/Testwuson.X";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  ModelOptions options;
  options.animation = "Wuson_Walk";
  const Scene walk = load_model(path.string(), options);
  EXPECT_NEAR(walk.time_end - walk.time_begin, 17280 / 4800.0, 1e-9);
  options.animation = "1";
  const Scene by_index = load_model(path.string(), options);
  EXPECT_EQ(by_index.time_end, walk.time_end);
  EXPECT_EQ(by_index.objects[0].key_positions.back(), walk.objects[0].key_positions.back());

  options.animation = "Wuson_Jump";
  try {
    (void)load_model(path.string(), options);
    FAIL() << "an unknown animation must be an InputError";
  } catch (const InputError& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("Testwuson.X"), std::string::npos) << message;
    EXPECT_NE(message.find("Wuson_Jump"), std::string::npos) << message;
    for (const char* name : {"0 'Wuson_Run'", "1 'Wuson_Walk'", "2 'Wuson_Bind'"})
      EXPECT_NE(message.find(name), std::string::npos) << message;
  }
  options.animation = "3";
  EXPECT_THROW((void)load_model(path.string(), options), InputError);
}

TEST(ModelKeyrate, ResamplesTheShotAtTheGivenRate) {
  const std::filesystem::path path = kTestModels / "X/Testwuson.X";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  ModelOptions options;
  options.keyrate = 10;
  const Scene scene = load_model(path.string(), options);
  const std::vector<double>& times = scene.objects.at(0).key_times;
  ASSERT_EQ(times.size(), 11u);  // 0, 0.1, ..., 0.9 and the last key 4640 / 4800 s
  for (size_t k = 0; k < 10; ++k) EXPECT_NEAR(times[k], 0.1 * double(k), 1e-12);
  EXPECT_NEAR(times.back(), 4640 / 4800.0, 1e-12);

  const Scene union_keys = load_model(path.string());
  EXPECT_EQ(union_keys.objects.at(0).key_count(), 30u);  // Wuson_Run has 30 keys per channel
  EXPECT_EQ(union_keys.objects[0].key_positions.back(), scene.objects[0].key_positions.back());

  options.keyrate = -1;
  EXPECT_THROW((void)load_model(path.string(), options), InputError);
  options.keyrate = 1e12;  // would be 1e12 keys
  EXPECT_THROW((void)load_model(path.string(), options), InputError);
}

TEST(ModelStatic, ModelWithoutAnimationIsStillForOneSecond) {
  const std::filesystem::path path = kTestModels / "OBJ/spider.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  const ScopedWarningSink quiet([](const std::string&) {});
  const Scene scene = load_model(path.string());
  EXPECT_EQ(scene.time_begin, 0);
  EXPECT_EQ(scene.time_end, 1);
  EXPECT_GT(scene.triangle_count(), 0u);
  for (const Object& object : scene.objects) EXPECT_EQ(object.key_count(), 1u);
  EXPECT_TRUE(bounds_in_view(scene, 0));
  ModelOptions options;
  options.animation = "run";
  EXPECT_THROW((void)load_model(path.string(), options), InputError);
}

TEST(ModelFiles, AssimpExtensionsAreModelFiles) {
  EXPECT_TRUE(is_model_file("a/b/robot.gltf"));
  EXPECT_TRUE(is_model_file("robot.GLB"));
  EXPECT_TRUE(is_model_file("robot.fbx"));
  EXPECT_TRUE(is_model_file("robot.dae"));
  EXPECT_TRUE(is_model_file("walk.bvh"));
  EXPECT_TRUE(is_model_file("guy.md5mesh"));
  EXPECT_TRUE(is_model_file("tiny.x"));
  EXPECT_FALSE(is_model_file("notes.txt"));
  EXPECT_FALSE(is_model_file("noextension"));
}

}  // namespace
}  // namespace kinray
