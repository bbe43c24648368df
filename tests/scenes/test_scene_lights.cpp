// Lights in scene files (read, saved and read again, mistakes named by key) and from models.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scenes/model_import.h"
#include "scenes/scene_file.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

std::string with_lights(const std::string& lights) {
  return R"({"shot": {"begin": 0, "end": 1},
             "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]},
             "lights": )" +
         lights + R"(,
             "objects": [{"kind": "sphere"}]})";
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene_file(text, "lights.json");
  } catch (const InputError& error) {
    return error.what();
  }
  return "no error";
}

TEST(SceneLights, ReadSavedAndReadAgain) {
  const Scene scene = parse_scene_file(with_lights(R"([
      {"kind": "point", "position": [1, 2.5, -3]},
      {"kind": "directional", "direction": [0, -2, 0], "color": [0.25, 0.5, 2]}])"),
                                       "lights.json");
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].kind, Light::Kind::point);
  EXPECT_EQ(scene.lights[0].position, Vec3(1, 2.5, -3));
  EXPECT_EQ(scene.lights[0].color, Color(1, 1, 1));
  EXPECT_EQ(scene.lights[1].kind, Light::Kind::directional);
  EXPECT_EQ(scene.lights[1].direction, Vec3(0, -1, 0));  // normalized
  EXPECT_EQ(scene.lights[1].color, Color(0.25f, 0.5f, 2.0f));

  const fs::path path =
      fs::temp_directory_path() / ("kinray_scene_lights_" + std::to_string(getpid()) + ".json");
  save_scene_file(scene, path.string());
  const Scene again = load_scene_file(path.string());
  fs::remove(path);
  ASSERT_EQ(again.lights.size(), 2u);
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(again.lights[l].kind, scene.lights[l].kind);
    EXPECT_EQ(again.lights[l].position, scene.lights[l].position);
    EXPECT_EQ(again.lights[l].direction, scene.lights[l].direction);
    EXPECT_EQ(again.lights[l].color, scene.lights[l].color);
  }
}

TEST(SceneLights, NoKeyMeansNoLights) {
  EXPECT_TRUE(parse_scene_file(with_lights("[]"), "lights.json").lights.empty());
}

TEST(SceneLights, MistakesNameTheKey) {
  struct Mistake {
    std::string lights, where, problem;
  };
  const std::vector<Mistake> mistakes = {
      {R"([{"kind": "spot", "position": [0, 0, 0]}])", "/lights/0/kind", "unknown light kind"},
      {R"([{"position": [0, 0, 0]}])", "/lights/0", "missing key 'kind'"},
      {R"([{"kind": "point"}])", "/lights/0", "missing key 'position'"},
      {R"([{"kind": "point", "position": [0, 0]}])", "/lights/0/position", "3 elements"},
      {R"([{"kind": "directional", "direction": [0, 0, 0]}])", "/lights/0/direction",
       "must not be zero"},
      {R"([{"kind": "point", "position": [0, 0, 0], "color": [1, -1, 1]}])", "/lights/0/color",
       ">= 0"},
      {R"([{"kind": "point", "position": [0, 0, 0], "direction": [0, 0, 1]}])",
       "/lights/0/direction", "unknown key"},
      {R"({"kind": "point"})", "/lights", "expected an array"},
  };
  for (const Mistake& m : mistakes) {
    const std::string message = error_of(with_lights(m.lights));
    EXPECT_NE(message.find("lights.json: " + m.where + ":"), std::string::npos) << message;
    EXPECT_NE(message.find(m.problem), std::string::npos) << message;
  }
}

TEST(SceneLights, ModelLightsArePlacedInWorldSpace) {
  // huesitos.fbx carries one light; it must arrive placed by its node, finite, not black.
  const fs::path model = "/usr/share/assimp/models/FBX/huesitos.fbx";
  if (!fs::exists(model)) GTEST_SKIP() << model << " is not installed";
  const Scene scene = load_model(model.string(), ModelOptions{});
  ASSERT_EQ(scene.lights.size(), 1u);
  const Light& light = scene.lights[0];
  EXPECT_TRUE(light.position.allFinite());
  EXPECT_TRUE(light.direction.allFinite());
  EXPECT_GT(light.color.maxCoeff(), 0.0f);
  // A file that brings the model takes its lights, unless it lists its own.
  const std::string file = R"({"objects": [{"kind": "model", "path": ")" + model.string() + "\"}]";
  EXPECT_EQ(parse_scene_file(file + "}", "m.json").lights.size(), 1u);
  EXPECT_EQ(parse_scene_file(file + R"(, "lights": []})", "m.json").lights.size(), 0u);
}

}  // namespace
}  // namespace kinray
