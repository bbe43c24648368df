// --camera auto|model, --eye/--target/--fov and `kinray info`'s animations and camera source, as a
// user runs them: the images they give, the projection of a known point, and one line for each
// bad value.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "renderer/frame.h"
#include "renderer/output/image_io.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = "/usr/share/assimp/models";

class CameraFlags : public test::CommandTest {
 protected:
  /// Skips the test when Debian's test model `name` is not installed; its path otherwise.
  std::string model(const char* name) {
    const fs::path path = kModels / name;
    if (!fs::exists(path)) return {};
    return "'" + path.string() + "'";
  }
};

TEST_F(CameraFlags, BadValuesAreOneLineNamingTheFlag) {
  const std::string render =
      "render wavy-sphere:triangles=600 --size 16x16 --frames 1 --out '" + path("f") + "' ";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"--camera front", "--camera: expected auto or model, got 'front'"},
      {"--camera auto --eye 0,0,5 --target 0,0,0", "--camera: cannot be combined with --eye"},
      {"--eye 0,0,5", "--eye: needs --target X,Y,Z too"},
      {"--target 0,0,0", "--target: needs --eye X,Y,Z too"},
      {"--eye nan,0,5 --target 0,0,0", "--eye: expected a point X,Y,Z"},
      {"--eye 0,0,5 --target 0,inf,0", "--target: expected a point X,Y,Z"},
      {"--eye 1,2 --target 0,0,0", "--eye: expected a point X,Y,Z"},
      {"--eye 1e16,0,0 --target 0,0,0", "--eye: coordinates must lie within +-1e15"},
      {"--eye 1,1,1 --target 1,1,1", "--target: is the eye itself (1,1,1)"},
      {"--fov 0", "--fov: expected the vertical field of view in degrees"},
      {"--fov 180", "--fov: expected the vertical field of view in degrees"},
      {"--fov -30", "--fov: expected the vertical field of view in degrees"},
      {"--fov nan", "--fov: expected the vertical field of view in degrees"},
      {"--fov wide", "--fov: expected the vertical field of view in degrees"},
  };
  for (const auto& [flags, line] : cases) {
    SCOPED_TRACE(flags);
    const test::CommandRun run = kinray(render + flags);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind("kinray: error: " + line, 0), 0u) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  EXPECT_FALSE(fs::exists(path("f")));
  // diff, bench and info take the same flags, checked the same way before any work.
  for (const std::string& command :
       {std::string("diff wavy-sphere:triangles=600 --size 16x16 --frames 1 --fov 0"),
        std::string("bench wavy-sphere:triangles=600 --size 16x16 --fov 0"),
        std::string("info wavy-sphere:triangles=600 --fov 0")}) {
    SCOPED_TRACE(command);
    const test::CommandRun run = kinray(command);
    EXPECT_EQ(run.status, 2);
    EXPECT_EQ(run.err.rfind("kinray: error: --fov: ", 0), 0u) << run.err;
  }
}

TEST_F(CameraFlags, CameraModelOnAModelWithoutOneIsAnError) {
  const std::string bvh = model("BVH/01_01.bvh");
  if (bvh.empty()) GTEST_SKIP() << "assimp-testmodels are not installed";
  const test::CommandRun run = kinray("render " + bvh + " --camera model --size 16x12 --frames 1 " +
                                      "--backend embree --out '" + path("f") + "'");
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err.rfind("kinray: error: --camera: model: ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find("has no perspective camera of its own"), std::string::npos) << run.err;
  EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  EXPECT_FALSE(fs::exists(path("f")));
}

TEST_F(CameraFlags, ModelAndAutoCamerasGiveDifferentImages) {
  const std::string fbx = model("FBX/animation_with_skeleton.fbx");
  if (fbx.empty()) GTEST_SKIP() << "assimp-testmodels are not installed";
  const auto render = [&](const std::string& name, const std::string& flags) {
    const test::CommandRun run =
        kinray("render " + fbx + " --backend embree --size 64x48 " +
               "--frames 1 --quiet --aov id --out '" + path(name) + "' " + flags);
    EXPECT_EQ(run.status, 0) << run.err;
    Frame frame;
    frame.resize(64, 48);
    read_id_png(path(name) + "/id_00000.png", frame);
    return frame.object;
  };
  const std::vector<uint32_t> by_default = render("default", ""),
                              own = render("model", "--camera model"),
                              framed = render("auto", "--camera auto");
  EXPECT_EQ(by_default, own) << "the model's own camera is the default when it sees the model";
  EXPECT_NE(own, framed);
  for (const auto* ids : {&own, &framed})
    EXPECT_GT(std::count_if(ids->begin(), ids->end(), [](uint32_t id) { return id != kNoHit; }), 20)
        << "both cameras see the model";
}

/// The issue's case: the BVH walk 01_01 framed by the bounds of the whole walk filled 35 to 78 of
/// the 19,200 pixels of a 160x120 frame (frames 0, 1/4, ... of the shot: 35 66 66 35 78); followed,
/// it fills 214 to 259. And the kinetic grid, audited, traces the moving camera as Embree does.
TEST_F(CameraFlags, AutomaticFramingFollowsABvhWalk) {
  const std::string bvh = model("BVH/01_01.bvh");
  if (bvh.empty()) GTEST_SKIP() << "assimp-testmodels are not installed";
  test::CommandRun run = kinray("render " + bvh + " --backend embree --size 160x120 --frames 5 " +
                                "--aov id --quiet --out '" + path("walk") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  for (int f = 0; f < 5; ++f) {
    Frame frame;
    frame.resize(160, 120);
    read_id_png(path("walk") + "/id_0000" + std::to_string(f) + ".png", frame);
    const auto filled = std::count_if(frame.object.begin(), frame.object.end(),
                                      [](uint32_t id) { return id != kNoHit; });
    EXPECT_GT(filled, 180) << "frame " << f;
  }
  run = kinray("diff " + bvh + " --size 48x36 --time 5:5.25 --frames 4 --audit --quiet");
  EXPECT_EQ(run.status, 0) << run.out << run.err;
}

/// A square of half-side 0.22 facing +z at (1, 0.5, 0), seen from --eye 0,0,5 --target 0,0,0
/// --fov 90 at 200x100: in camera space its centre is (1, 0.5) at depth 5, so the image-plane
/// coordinates are x/z = 0.2, y/z = 0.1 (tan 45 = 1); a pixel centre is at
/// x = ((2i+1)/200 - 1) * 2 and y = 1 - (2j+1)/100, so the square covers the centres of columns
/// 108..111 (x in [0.156, 0.244]) and rows 43..46 (y in [0.056, 0.144]), and no other.
TEST_F(CameraFlags, AnExplicitCameraProjectsAKnownPointAnalytically) {
  const std::string scene = path("square.json");
  std::ofstream(scene) << R"({
    "shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"time": 0, "position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 30}]},
    "objects": [{"kind": "mesh", "name": "square",
                 "vertices": [[0.78, 0.28, 0], [1.22, 0.28, 0], [1.22, 0.72, 0], [0.78, 0.72, 0]],
                 "triangles": [[0, 1, 2], [0, 2, 3]]}]
  })";
  for (const char* backend : {"embree", "kinetic"}) {
    SCOPED_TRACE(backend);
    const test::CommandRun run = kinray(
        "render '" + scene + "' --backend " + backend + " --size 200x100 --frames 1 " +
        "--eye 0,0,5 --target 0,0,0 --fov 90 --aov id --quiet --out '" + path(backend) + "'");
    ASSERT_EQ(run.status, 0) << run.err;
    Frame frame;
    frame.resize(200, 100);
    read_id_png(path(backend) + "/id_00000.png", frame);
    std::set<std::pair<int, int>> covered, expected;
    for (int j = 0; j < 100; ++j)
      for (int i = 0; i < 200; ++i)
        if (frame.object[frame.index(i, j)] != kNoHit) covered.emplace(i, j);
    for (int j = 43; j <= 46; ++j)
      for (int i = 108; i <= 111; ++i) expected.emplace(i, j);
    EXPECT_EQ(covered, expected);
  }
  // The scene's own camera (behind the square, narrow) sees it elsewhere: the flags took effect.
  const test::CommandRun own = kinray("render '" + scene + "' --backend embree --size 200x100 " +
                                      "--frames 1 --aov id --quiet --out '" + path("own") + "'");
  ASSERT_EQ(own.status, 0) << own.err;
  Frame frame;
  frame.resize(200, 100);
  read_id_png(path("own") + "/id_00000.png", frame);
  EXPECT_EQ(frame.object[frame.index(109, 44)], kNoHit);
}

TEST_F(CameraFlags, InfoListsTheAnimationsAndWhereTheCameraComesFrom) {
  const std::string wuson = model("X/Testwuson.X");
  if (wuson.empty()) GTEST_SKIP() << "assimp-testmodels are not installed";
  test::CommandRun run = kinray("info " + wuson + " --json");
  ASSERT_EQ(run.status, 0) << run.err;
  nlohmann::json info = nlohmann::json::parse(run.out);
  // The file: AnimTicksPerSecond 4800; Wuson_Run keyed 0..4640, Wuson_Walk 0..17280 (as the
  // import tests read them off the file), one channel per animated frame of the 12 bones.
  const nlohmann::json& animations = info["animations"];
  ASSERT_EQ(animations.size(), 3u);
  const std::vector<std::string> names = {"Wuson_Run", "Wuson_Walk", "Wuson_Bind"};
  for (size_t a = 0; a < 3; ++a) {
    EXPECT_EQ(animations[a]["index"], a);
    EXPECT_EQ(animations[a]["name"], names[a]);
    EXPECT_EQ(animations[a]["morph_channels"], 0);
    EXPECT_GT(animations[a]["node_channels"].get<int>(), 0);
    EXPECT_EQ(animations[a]["default"], a == 0);
  }
  EXPECT_NEAR(animations[0]["duration"].get<double>(), 4640 / 4800.0, 1e-9);
  EXPECT_NEAR(animations[1]["duration"].get<double>(), 17280 / 4800.0, 1e-9);
  EXPECT_DOUBLE_EQ(info["duration"].get<double>(), animations[0]["duration"].get<double>());
  EXPECT_EQ(info["camera_source"]["kind"], "automatic");
  EXPECT_EQ(info["camera_source"]["reason"], "the model has no camera");

  run = kinray("info " + wuson + " --animation Wuson_Walk");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("animations  3 (render plays 0 by default"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("'Wuson_Walk'"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("3.6 s"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("shown here"), std::string::npos) << run.out;
  EXPECT_NE(run.out.find("camera      automatic framing"), std::string::npos) << run.out;

  // A glTF morph animation counts its morph channel; an FBX keeps its own camera, by name.
  if (const std::string cube = model("glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/"
                                     "AnimatedMorphCube.gltf");
      !cube.empty()) {
    run = kinray("info " + cube + " --json");
    ASSERT_EQ(run.status, 0) << run.err;
    info = nlohmann::json::parse(run.out);
    ASSERT_EQ(info["animations"].size(), 1u);
    EXPECT_EQ(info["animations"][0]["morph_channels"], 1);
    EXPECT_NEAR(info["animations"][0]["duration"].get<double>(), 4.2, 1e-5);
  }
  run = kinray("info " + model("FBX/animation_with_skeleton.fbx") + " --json");
  ASSERT_EQ(run.status, 0) << run.err;
  info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["camera_source"]["kind"], "model");
  EXPECT_EQ(info["camera_source"]["name"], info["model_cameras"][0]);
  run = kinray("info " + model("FBX/animation_with_skeleton.fbx") + " --camera auto --json");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(nlohmann::json::parse(run.out)["camera_source"]["kind"], "automatic");

  // Built-ins and scene files: their own camera, or what the flags ask for.
  run = kinray("info wavy-sphere:triangles=600 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["camera_source"]["kind"], "scene");
  EXPECT_FALSE(info.contains("animations"));
  run = kinray("info wavy-sphere:triangles=600 --eye 0,0,9 --target 0,0,0 --fov 30 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["camera_source"]["kind"], "command line");
  EXPECT_EQ(info["camera_keys"][0]["position"], nlohmann::json({0, 0, 9}));
  EXPECT_EQ(info["camera_keys"][0]["fov_y_degrees"], 30);
  // --fov alone changes the field of view of whichever camera is used; automatic framing is
  // placed again for it, farther away for a narrower view.
  run = kinray("info flythrough:triangles=2000 --fov 20 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["camera_source"]["kind"], "scene");
  ASSERT_GT(info["camera_keys"].size(), 1u);
  for (const auto& key : info["camera_keys"]) EXPECT_EQ(key["fov_y_degrees"], 20);
  const auto eye_distance = [&](const std::string& flags) {
    const test::CommandRun framed = kinray("info " + wuson + " --json " + flags);
    EXPECT_EQ(framed.status, 0) << framed.err;
    const nlohmann::json keys = nlohmann::json::parse(framed.out)["camera_keys"];
    EXPECT_EQ(keys.size(), 1u);
    const nlohmann::json p = keys[0]["position"];
    return std::make_pair(keys[0]["fov_y_degrees"].get<double>(),
                          std::hypot(p[0].get<double>(), p[1].get<double>(), p[2].get<double>()));
  };
  const auto [wide_fov, wide] = eye_distance("");
  const auto [narrow_fov, narrow] = eye_distance("--fov 22.5");
  EXPECT_EQ(wide_fov, 45);
  EXPECT_EQ(narrow_fov, 22.5);
  EXPECT_GT(narrow, 1.8 * wide);  // sin(22.5 / 2) against sin(45 / 2): about twice as far

  run = kinray("info wavy-sphere:triangles=600 --camera auto");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("camera      automatic framing, still (--camera auto)"), std::string::npos)
      << run.out;
}

}  // namespace
}  // namespace kinray
