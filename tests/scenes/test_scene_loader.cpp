// Naming a scene: built-ins with parameters, scene files, model files, and the errors for
// everything else.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scenes/procedural.h"
#include "scenes/scene_loader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

std::string error_of(const std::string& spec) {
  try {
    (void)load_scene(spec);
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError for '" << spec << "'";
  return "";
}

TEST(SceneLoader, BuiltinNamesWithParameters) {
  const Scene cloth = load_scene("cloth:triangles=2000,duration=1.5");
  EXPECT_EQ(cloth.name, "cloth");
  EXPECT_EQ(cloth.time_end, 1.5);
  EXPECT_NEAR(double(cloth.triangle_count()), 2000, 200);

  const Scene wavy = load_scene("wavy-sphere:triangles=600");
  const Scene direct = make_builtin_scene("wavy-sphere", {{"triangles", 600}});
  EXPECT_EQ(wavy.objects[0].key_positions, direct.objects[0].key_positions);

  EXPECT_EQ(load_scene("orbit:keyrate=10,duration=1,triangles=500").key_times().size(), 11u);
  EXPECT_EQ(load_scene("flythrough:triangles=1e3").camera.keys.size(), 97u);  // 4 s at 24 keys/s
}

TEST(SceneLoader, BadBuiltinSpecs) {
  EXPECT_NE(error_of("cloth:triangles=abc").find("parameter triangles needs a number, got 'abc'"),
            std::string::npos);
  EXPECT_NE(error_of("cloth:triangles").find("expected key=value"), std::string::npos);
  EXPECT_NE(error_of("cloth:size=3").find("the parameters are triangles, duration, keyrate"),
            std::string::npos);
  EXPECT_NE(error_of("cloth:duration=1,duration=2").find("given twice"), std::string::npos);
  EXPECT_NE(error_of("cloth:duration=0").find("duration must be a finite number > 0"),
            std::string::npos);
  EXPECT_NE(error_of("cloth:duration=nan").find("duration"), std::string::npos);
  const std::string unknown = error_of("teapot");
  EXPECT_NE(unknown.find("teapot"), std::string::npos);
  EXPECT_NE(unknown.find("wavy-sphere, cloth, orbit, flythrough, static-moving"),
            std::string::npos);
  EXPECT_NE(error_of("").find("empty scene name"), std::string::npos);
}

TEST(SceneLoader, SceneFilesAndModels) {
  const std::string example =
      std::string(KINRAY_SOURCE_DIR) + "/scenes/examples/static-moving.json";
  const Scene file = load_scene(example);
  EXPECT_EQ(file.name, "static-moving");
  EXPECT_EQ(file.objects.size(), 4u);

  const Scene model = load_scene("/usr/share/assimp/models/OBJ/box.obj");
  EXPECT_EQ(model.triangle_count(), 12u);
  EXPECT_NO_THROW(model.validate("box.obj"));
}

TEST(SceneLoader, MissingAndUnreadableFilesAreNamed) {
  const std::string missing_json = error_of("/nonexistent/dir/scene.json");
  EXPECT_NE(missing_json.find("/nonexistent/dir/scene.json"), std::string::npos);
  EXPECT_NE(missing_json.find("no such scene file"), std::string::npos);
  const std::string missing_model = error_of("models/missing.gltf");
  EXPECT_NE(missing_model.find("models/missing.gltf: no such file"), std::string::npos);

  const fs::path text =
      fs::temp_directory_path() / ("kinray_scene_loader_" + std::to_string(getpid()) + ".txt");
  std::ofstream(text) << "not a scene";
  const std::string not_a_scene = error_of(text.string());
  fs::remove(text);
  EXPECT_NE(not_a_scene.find(text.string()), std::string::npos);
  EXPECT_NE(not_a_scene.find("neither a scene file"), std::string::npos);
  // a folder is a mesh sequence (scenes/mesh_sequence.h): one without mesh files is refused
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_scene_loader_" + std::to_string(getpid()) + "_folder");
  fs::create_directories(folder);
  const std::string empty_folder = error_of(folder.string());
  fs::remove(folder);
  EXPECT_EQ(empty_folder, folder.string() + ": holds no .ply or .obj files (an empty sequence)");
}

TEST(SceneLoader, DescribesTheSyntaxAndEveryBuiltin) {
  const std::string help = describe_scene_spec_syntax();
  for (const BuiltinScene& scene : builtin_scenes()) {
    EXPECT_NE(help.find(scene.name + " [triangles="), std::string::npos) << scene.name;
    EXPECT_NE(help.find(scene.description), std::string::npos);
  }
  EXPECT_NE(help.find(".json"), std::string::npos);
}

}  // namespace
}  // namespace kinray
