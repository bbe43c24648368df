// JSON scene files: what each construct produces, that every example file loads and round-trips
// through save_scene_file, and that each kind of mistake is one InputError naming the file, the
// JSON pointer and the problem.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "scenes/procedural.h"
#include "scenes/scene_file.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const fs::path kExamples = fs::path(KINRAY_SOURCE_DIR) / "scenes" / "examples";

/// A fresh folder under the system temp dir, removed with the fixture.
class SceneFile : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_scene_file_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  std::string write(const std::string& name, const std::string& text) const {
    const fs::path path = m_dir / name;
    std::ofstream(path) << text;
    return path.string();
  }

  /// The message of the InputError that loading `text` must throw.
  std::string error_of(const std::string& text, const std::string& name = "bad.json") const {
    const std::string path = write(name, text);
    try {
      (void)load_scene_file(path);
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(path), std::string::npos) << error.what();
      return error.what();
    }
    ADD_FAILURE() << "no InputError for " << text;
    return "";
  }

  fs::path m_dir;
};

/// A minimal valid file around the given objects.
std::string with_objects(const std::string& objects) {
  return R"({"shot": {"begin": 0, "end": 1},
             "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]},
             "objects": [)" +
         objects + "]}";
}

const char* kTriangle =
    R"({"kind": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]]})";

void expect_same_scene(const Scene& a, const Scene& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.time_begin, b.time_begin);
  EXPECT_EQ(a.time_end, b.time_end);
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t m = 0; m < a.materials.size(); ++m) {
    EXPECT_EQ(a.materials[m].name, b.materials[m].name);
    EXPECT_EQ(a.materials[m].base_color, b.materials[m].base_color);
    EXPECT_EQ(a.materials[m].texture, b.materials[m].texture);
  }
  ASSERT_EQ(a.lights.size(), b.lights.size());
  for (size_t l = 0; l < a.lights.size(); ++l) {
    EXPECT_EQ(a.lights[l].kind, b.lights[l].kind);
    EXPECT_EQ(a.lights[l].position, b.lights[l].position);
    EXPECT_EQ(a.lights[l].direction, b.lights[l].direction);
    EXPECT_EQ(a.lights[l].color, b.lights[l].color);
  }
  ASSERT_EQ(a.textures.size(), b.textures.size());
  for (size_t t = 0; t < a.textures.size(); ++t) {
    EXPECT_EQ(a.textures[t].width, b.textures[t].width);
    EXPECT_EQ(a.textures[t].height, b.textures[t].height);
    EXPECT_EQ(a.textures[t].texels, b.textures[t].texels);
  }
  ASSERT_EQ(a.camera.keys.size(), b.camera.keys.size());
  for (size_t k = 0; k < a.camera.keys.size(); ++k) {
    EXPECT_EQ(a.camera.keys[k].time, b.camera.keys[k].time);
    EXPECT_EQ(a.camera.keys[k].position, b.camera.keys[k].position);
    EXPECT_EQ(a.camera.keys[k].orientation.coeffs(), b.camera.keys[k].orientation.coeffs());
    EXPECT_EQ(a.camera.keys[k].fov_y_degrees, b.camera.keys[k].fov_y_degrees);
  }
  ASSERT_EQ(a.objects.size(), b.objects.size());
  for (size_t o = 0; o < a.objects.size(); ++o) {
    const Object &x = a.objects[o], &y = b.objects[o];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.triangles, y.triangles);
    EXPECT_EQ(x.key_times, y.key_times);
    EXPECT_EQ(x.key_positions, y.key_positions) << x.name;
    EXPECT_EQ(x.uvs, y.uvs);
    EXPECT_EQ(x.material, y.material);
    EXPECT_EQ(x.appear, y.appear);
    EXPECT_EQ(x.disappear, y.disappear);
  }
}

TEST_F(SceneFile, EveryExampleLoadsAndRoundTrips) {
  size_t examples = 0;
  for (const auto& entry : fs::directory_iterator(kExamples)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    ++examples;
    const Scene scene = load_scene_file(entry.path().string());
    EXPECT_GT(scene.triangle_count(), 0u);
    EXPECT_FALSE(scene.key_times().size() < 3) << "every example is animated";
    const std::string copy = (m_dir / entry.path().filename()).string();
    save_scene_file(scene, copy);
    expect_same_scene(scene, load_scene_file(copy));
  }
  EXPECT_GE(examples, 8u);
}

TEST_F(SceneFile, BuiltinObjectsReproduceTheBuiltinScene) {
  expect_same_scene(load_scene_file((kExamples / "wavy-sphere.json").string()),
                    make_builtin_scene("wavy-sphere"));
  const std::string path = write("cloth.json", R"({"objects": [{"kind": "builtin", "scene": "cloth",
                                                   "params": {"triangles": 800, "duration": 1}}]})");
  expect_same_scene(load_scene_file(path), [] {
    Scene scene = make_builtin_scene("cloth", {{"triangles", 800}, {"duration", 1}});
    scene.name = "cloth";  // the file's stem
    return scene;
  }());
  // Every built-in, written out and read back as inline meshes.
  for (const std::string& name : builtin_scene_names()) {
    const Scene builtin = make_builtin_scene(name, {{"triangles", 600}, {"duration", 0.5}});
    const std::string copy = (m_dir / (name + ".json")).string();
    save_scene_file(builtin, copy);
    expect_same_scene(builtin, load_scene_file(copy));
  }
}

TEST_F(SceneFile, InlineMeshWithVertexKeys) {
  const Scene scene = load_scene_file(write("mesh.json", with_objects(R"(
    {"kind": "mesh", "name": "tri", "appear": 0.25, "disappear": 0.75,
     "triangles": [[0, 1, 2]], "uvs": [[0, 0], [1, 0], [0, 1]],
     "keys": [{"time": 0, "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]]},
              {"time": 0.5, "vertices": [[0, 0, 1], [1, 0, 1], [0, 1, 1]]}]})")));
  ASSERT_EQ(scene.objects.size(), 1u);
  const Object& tri = scene.objects[0];
  EXPECT_EQ(tri.name, "tri");
  EXPECT_EQ(tri.key_times, (std::vector<double>{0, 0.5}));
  EXPECT_EQ(tri.position(1, 0.25), Vec3(1, 0, 0.5));
  EXPECT_EQ(tri.uvs[2], Vec2f(0, 1));
  EXPECT_EQ(tri.appear, 0.25);
  EXPECT_EQ(tri.disappear, 0.75);
  ASSERT_EQ(scene.materials.size(), 1u);  // the default material, made for the mesh
}

TEST_F(SceneFile, TransformThenTransformKeysOrbitAPrimitive) {
  // A box placed at x = 2 by 'transform', then turned about the world's y axis by the keys:
  // a quarter turn per second, resampled at 8 keys per second.
  const Scene scene = load_scene_file(write("orbit.json", with_objects(R"(
    {"kind": "box", "size": 0.5, "transform": {"translation": [2, 0, 0]},
     "keys": [{"time": 0}, {"time": 1, "rotation": {"axis": [0, 1, 0], "degrees": 90}}], "keyrate": 8})")));
  const Object& box = scene.objects[0];
  ASSERT_EQ(box.key_count(), 9u);
  EXPECT_DOUBLE_EQ(box.key_times[3], 0.375);
  for (size_t k = 0; k < box.key_count(); ++k) {
    Vec3 centre = Vec3::Zero();
    for (const Vec3& p : box.key_positions[k]) centre += p / double(box.vertex_count());
    EXPECT_NEAR(centre.norm(), 2.0, 1e-12) << "the orbit stays round at key " << k;
    EXPECT_NEAR(centre.y(), 0.0, 1e-12);
  }
  Vec3 end = Vec3::Zero();
  for (const Vec3& p : box.key_positions.back()) end += p / double(box.vertex_count());
  EXPECT_NEAR((end - Vec3(0, 0, -2)).norm(), 0.0, 1e-12);  // +x turned a quarter about +y is -z
}

TEST_F(SceneFile, PrimitivesMaterialsAndTextures) {
  const std::string texture =
      fs::relative("/usr/share/assimp/models/OBJ/wal67ar_small.jpg", m_dir).string();
  const Scene scene = load_scene_file(write("prims.json", R"({
    "shot": {"begin": 0, "end": 1},
    "materials": [{"name": "red", "base_color": [1, 0, 0]},
                  {"name": "wall", "texture": ")" + texture + R"("}],
    "camera": {"keys": [{"position": [0, 0, -5], "orientation": [1, 0, 0, 0], "fov_y": 30}]},
    "objects": [{"kind": "sphere", "radius": 2, "triangles": 300},
                {"kind": "grid", "material": "wall", "size": [4, 2], "subdivisions": [4, 2]},
                {"kind": "box", "material": 0, "size": [1, 2, 3], "subdivisions": 2,
                 "transform": {"scale": 2, "rotation": [0, 0, 1, 0]}}]})"));
  ASSERT_EQ(scene.objects.size(), 3u);
  EXPECT_EQ(scene.objects[0].triangles.size(), 300u);  // 12 * 5^2
  for (const Vec3& p : scene.objects[0].key_positions[0]) EXPECT_NEAR(p.norm(), 2.0, 1e-12);
  EXPECT_EQ(scene.objects[0].material, 0u);
  EXPECT_EQ(scene.objects[1].triangles.size(), 16u);
  EXPECT_EQ(scene.objects[1].material, 1u);
  EXPECT_EQ(scene.objects[1].uvs.size(), 15u);
  EXPECT_EQ(scene.objects[2].triangles.size(), 48u);
  const Eigen::AlignedBox3d box_bounds = [&] {
    Eigen::AlignedBox3d b;
    for (const Vec3& p : scene.objects[2].key_positions[0]) b.extend(p);
    return b;
  }();
  EXPECT_NEAR((box_bounds.sizes() - Vec3(2, 4, 6)).norm(), 0, 1e-12);
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_GT(scene.textures[0].width, 0);
  EXPECT_EQ(scene.materials[1].texture, 0);
  EXPECT_EQ(scene.materials[0].base_color, Color(1, 0, 0));
  EXPECT_EQ(scene.camera.keys[0].fov_y_degrees, 30);
  EXPECT_EQ(scene.camera.keys[0].orientation.coeffs(), Eigen::Quaterniond::Identity().coeffs());
}

TEST_F(SceneFile, CameraKeysLookAtAndResampling) {
  const Scene scene = load_scene_file(write("camera.json", R"({
    "shot": {"begin": 0, "end": 2},
    "camera": {"keyrate": 4, "keys": [
      {"time": 0, "position": [0, 0, -5], "look_at": [0, 0, 0], "up": [0, 1, 0], "fov_y": 40},
      {"time": 2, "position": [5, 0, 0], "look_at": [0, 0, 0], "fov_y": 60}]},
    "objects": [)" + std::string(kTriangle) + "]}"));
  const Camera& camera = scene.camera;
  ASSERT_EQ(camera.keys.size(), 9u);
  const CameraKey expected = Camera::look_at(0, Vec3(0, 0, -5), Vec3::Zero(), Vec3::UnitY(), 40);
  EXPECT_EQ(camera.keys[0].orientation.coeffs(), expected.orientation.coeffs());
  EXPECT_EQ(camera.keys[8].position, Vec3(5, 0, 0));
  EXPECT_DOUBLE_EQ(camera.keys[4].time, 1.0);
  EXPECT_DOUBLE_EQ(camera.keys[4].fov_y_degrees, 50.0);
  EXPECT_EQ(scene.key_times().size(), 9u);
}

TEST_F(SceneFile, ModelObjectsArePlacedAndKeyed) {
  const Scene scene = load_scene_file((kExamples / "models.json").string());
  size_t spider = 0, morph = 0;
  for (const Object& object : scene.objects) {
    spider += object.name.rfind("spider/", 0) == 0;
    if (object.name.rfind("morph/", 0) == 0) {
      ++morph;
      EXPECT_GT(object.key_count(), 40u);  // the morph animation, resampled at 24 keys per second
    }
  }
  EXPECT_GT(spider, 1u);
  EXPECT_EQ(morph, 1u);
  // Scaled from centimetres to about two metres, and turning.
  const Eigen::AlignedBox3d bounds = scene.bounds();
  EXPECT_LT(bounds.sizes().maxCoeff(), 12.0);
}

TEST_F(SceneFile, SyntaxErrorsNameLineAndColumn) {
  const std::string message = error_of("{\n  \"shot\": {\"begin\": 0,, \"end\": 1}\n}");
  EXPECT_NE(message.find("bad.json:2:"), std::string::npos) << message;
  EXPECT_NE(message.find("syntax error"), std::string::npos) << message;
  const std::string overflow =
      error_of(with_objects(R"({"kind": "mesh", "vertices": [[0, 0, 1e999]], "triangles": []})"));
  EXPECT_NE(overflow.find("bad.json:3:"), std::string::npos) << overflow;
  EXPECT_NE(overflow.find("1e999"), std::string::npos) << overflow;
  EXPECT_NE(error_of("").find("syntax error"), std::string::npos);
}

struct Mistake {
  const char* what;
  std::string text;
  const char* pointer;
  const char* problem;
};

TEST_F(SceneFile, MistakesNameTheFileTheKeyAndTheProblem) {
  const std::string base =
      R"("shot": {"begin": 0, "end": 1}, "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]})";
  const std::vector<Mistake> mistakes = {
      {"missing key", with_objects(R"({"vertices": [[0, 0, 0]], "triangles": []})"),
       "/objects/0:", "missing key 'kind'"},
      {"missing camera position",
       R"({"shot": {"begin": 0, "end": 1}, "camera": {"keys": [{"look_at": [0, 0, 0]}]}, "objects": []})",
       "/camera/keys/0:", "missing key 'position'"},
      {"missing camera", R"({"shot": {"begin": 0, "end": 1}, "objects": []})",
       "bad.json: missing key 'camera'", "only a file with a builtin"},
      {"NaN vertex (JSON writes NaN as null)",
       with_objects(
           R"({"kind": "mesh", "vertices": [[0, 0, 0], [1, 0, null], [0, 1, 0]], "triangles": [[0, 1, 2]]})"),
       "/objects/0/vertices/1/2:", "expected a number, got null"},
      {"index out of range",
       with_objects(
           R"({"kind": "mesh", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2], [0, 1, 3]]})"),
       "/objects/0/triangles/1/2:", "vertex index 3 out of range (3 vertices)"},
      {"negative index",
       with_objects(R"({"kind": "mesh", "vertices": [[0, 0, 0]], "triangles": [[0, -1, 0]]})"),
       "/objects/0/triangles/0/1:", "expected an integer >= 0"},
      {"unsorted key times",
       with_objects(R"({"kind": "sphere", "keys": [{"time": 0}, {"time": 1}, {"time": 0.5}]})"),
       "/objects/0/keys/2/time:", "(unsorted)"},
      {"duplicate key times",
       with_objects(
           R"({"kind": "mesh", "triangles": [], "keys": [{"time": 0, "vertices": [[0, 0, 0]]}, {"time": 0, "vertices": [[1, 0, 0]]}]})"),
       "/objects/0/keys/1/time:", "(duplicate)"},
      {"duplicate camera key times",
       R"({"shot": {"begin": 0, "end": 1}, "camera": {"keys": [{"time": 1, "position": [0, 0, -5], "look_at": [0, 0, 0]},
          {"time": 1, "position": [0, 0, -4], "look_at": [0, 0, 0]}]}, "objects": []})",
       "/camera/keys/1/time:", "(duplicate)"},
      {"zero-length shot",
       R"({"shot": {"begin": 1, "end": 1}, "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]}, "objects": []})",
       "/shot/end:", "must end after it begins"},
      {"unknown object kind", with_objects(R"({"kind": "cylinder"})"),
       "/objects/0/kind:", "unknown object kind 'cylinder'"},
      {"unknown key", with_objects(R"({"kind": "sphere", "radious": 2})"),
       "/objects/0/radious:", "unknown key 'radious'"},
      {"wrong type", "{" + base + R"(, "objects": [{"kind": "sphere", "radius": "big"}]})",
       "/objects/0/radius:", "expected a number, got string"},
      {"vertex count differs between keys",
       with_objects(
           R"({"kind": "mesh", "triangles": [], "keys": [{"time": 0, "vertices": [[0, 0, 0]]}, {"time": 1, "vertices": [[0, 0, 0], [1, 1, 1]]}]})"),
       "/objects/0/keys/1/vertices:", "has 2 vertices, key 0 has 1"},
      {"mixed key kinds",
       with_objects(
           R"({"kind": "mesh", "triangles": [], "keys": [{"time": 0, "vertices": [[0, 0, 0]]}, {"time": 1, "translation": [1, 0, 0]}]})"),
       "/objects/0/keys/1:", "missing key 'vertices'"},
      {"unknown material",
       "{" + base +
           R"(, "materials": [{"name": "red"}], "objects": [{"kind": "box", "material": "blue"}]})",
       "/objects/0/material:", "no material called 'blue'; the materials are red"},
      {"missing texture",
       "{" + base + R"(, "materials": [{"texture": "nowhere.png"}], "objects": []})",
       "/materials/0/texture:", "no such file"},
      {"missing model", with_objects(R"({"kind": "model", "path": "nowhere.gltf"})"),
       "/objects/0/path:", "no such file"},
      {"unknown builtin", with_objects(R"({"kind": "builtin", "scene": "teapot"})"),
       "/objects/0/scene:", "unknown built-in scene"},
      {"bad builtin parameter",
       with_objects(R"({"kind": "builtin", "scene": "cloth", "params": {"triangles": -3}})"),
       "/objects/0/params:", "triangles must be a finite number > 0"},
      {"fov out of range",
       R"({"shot": {"begin": 0, "end": 1}, "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 180}]}, "objects": []})",
       "/camera/keys/0/fov_y:", "fov_y must lie in (0.5, 179.5)"},
      {"look_at and orientation",
       R"({"shot": {"begin": 0, "end": 1}, "camera": {"keys": [{"position": [0, 0, -5]}]}, "objects": []})",
       "/camera/keys/0:", "give either 'look_at'"},
      {"disappears before it appears",
       with_objects(R"({"kind": "sphere", "appear": 1, "disappear": 0.5})"),
       "/objects/0/disappear:", "must disappear after it appears"},
      {"zero quaternion",
       with_objects(R"({"kind": "sphere", "transform": {"rotation": [0, 0, 0, 0]}})"),
       "/objects/0/transform/rotation:", "must not be zero"},
      {"not an object at the top", "[1, 2]", "bad.json: expected an object", "got array"},
  };
  for (const Mistake& mistake : mistakes) {
    SCOPED_TRACE(mistake.what);
    const std::string message = error_of(mistake.text);
    EXPECT_NE(message.find(mistake.pointer), std::string::npos) << message;
    EXPECT_NE(message.find(mistake.problem), std::string::npos) << message;
  }
}

TEST_F(SceneFile, ATextureOpenCvMustNotDecodeIsAnInputError) {
  // An OpenEXR header under a .png name: OpenCV would hand it to OpenEXR, whose decoders abort on
  // malformed input, so the reader refuses any file that is not one of the formats it names.
  write("fake.png", std::string("\x76\x2f\x31\x01\x02\0\0\0", 8));
  const std::string message = error_of(R"({"shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]},
    "materials": [{"texture": "fake.png"}], "objects": []})");
  EXPECT_NE(message.find("/materials/0/texture:"), std::string::npos) << message;
  EXPECT_NE(message.find("fake.png (not a PNG, JPEG, BMP, TIFF, PNM or WebP file)"),
            std::string::npos)
      << message;
}

TEST_F(SceneFile, MissingFileIsAnInputError) {
  const std::string path = (m_dir / "absent.json").string();
  try {
    (void)load_scene_file(path);
    FAIL() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find(path), std::string::npos);
    EXPECT_NE(std::string(error.what()).find("no such scene file"), std::string::npos);
  }
}

}  // namespace
}  // namespace kinray
