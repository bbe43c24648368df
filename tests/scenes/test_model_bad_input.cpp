// Bad models never crash or hang kinray: each is one InputError naming the file and the problem,
// or a documented repair (docs/models.md). The table says which, file by file.
#include <assimp/scene.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <latch>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "scenes/model_guard.h"
#include "scenes/model_import.h"
#include "tests/address_sanitizer.h"
#include "tests/scenes/model_test_support.h"
#include "util/input_error.h"
#include "util/parallel.h"
#include "util/warning.h"

namespace kinray {
namespace {

using testing::kSharedModels;
using testing::kTestModels;

struct BadModel {
  const char* path;      ///< under kTestModels, or kSharedModels when `shared`
  const char* problem;   ///< a piece of the InputError's message, or nullptr: repaired, it loads
  size_t triangles = 0;  ///< when repaired
  bool shared = false;
};

void PrintTo(const BadModel& model, std::ostream* out) {
  *out << model.path;
}

const std::vector<BadModel> kBadModels = {
    // invalid/readme.txt: "OutOfMemory.off - the number of faces is invalid", "empty.<x> -
    // completely empty", "malformed.obj - out-of-range vertex indices", "malformed2.obj -
    // non-existent material referenced".
    // Its face count makes the OFF reader allocate ~16 GB: the reading child's address-space
    // limit turns that into a prompt bad_alloc (or, with room to spare, assimp rejects the faces).
    {"invalid/OutOfMemory.off", "assimp cannot read it"},
    {"invalid/empty.3ds", "empty"},
    {"invalid/empty.ase", "empty"},
    {"invalid/empty.lwo", "too small"},
    {"invalid/empty.md5mesh", "MD5"},
    {"invalid/empty.obj", "too small"},
    {"invalid/empty.off", "empty"},
    {"invalid/empty.ply", "empty"},
    {"invalid/empty.raw", "empty"},
    {"invalid/empty.smd", "empty"},
    {"invalid/empty.x", "too small"},
    {"invalid/emptyIrrMesh.xml", "Unable to read a mesh"},
    {"invalid/malformed.obj", "Invalid face index"},
    {"invalid/malformed2.obj", nullptr, 10},  // assimp gives the faces its default material
    {"invalid/readme.txt", "No suitable reader"},
    // Elsewhere in the test set: infinite vertices, indices out of range, broken structure.
    {"glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb", "NaN or infinite"},
    {"glTF2/IndexOutOfRange/IndexOutOfRange.gltf", nullptr,
     11},  // assimp drops the one bad face of 12
    {"glTF2/IndexOutOfRange/AllIndicesOutOfRange.gltf", "no faces"},
    {"glTF2/MissingBin/BoxTextured.gltf", "BoxTextured0.bin"},
    {"glTF2/RecursiveNodes/RecursiveNodes.gltf", "recursive"},
    {"glTF2/TestNoRootNode/NoScene.gltf", "No scene"},
    {"glTF2/TestNoRootNode/SceneWithoutNodes.gltf", "no triangles"},
    {"glTF2/SchemaFailures/sceneWrongType.gltf", "not of type"},
    {"glTF2/wrongTypes/badArray.gltf", "not of type"},
    {"glTF2/issue_3269/texcoord_crash.gltf", "TEXCOORD_1"},
    {"FBX/transparentTest.fbx", "out of range"},
    {"OBJ/point_cloud.obj", "no faces"},
    {"OpenGEX/empty_camera.ogex", "nullptr"},  // its loader also prints to stdout: sent to stderr
    // assimp 5.2's X reader writes out of bounds on skin weights past the vertices (a SIGSEGV, or
    // silent corruption, depending on the heap): text .x files are checked before assimp reads
    // them.
    {"X/malformed_skinweights_oob.x", "weighs vertex 1000000, but the mesh has 24 vertices", 0,
     true},
};

class BadModels : public ::testing::TestWithParam<BadModel> {};

TEST_P(BadModels, FailWithOneInputErrorOrLoadRepaired) {
  const BadModel& model = GetParam();
  const std::filesystem::path path = (model.shared ? kSharedModels : kTestModels) / model.path;
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " is not installed";
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();  // assimp's own output, sent to stderr (model_guard.h)
  std::string error;
  Scene scene;
  try {
    scene = load_model(path.string());
  } catch (const InputError& failure) {
    error = failure.what();
  }
  const std::string out = ::testing::internal::GetCapturedStdout();
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(out, "") << "nothing of assimp's may reach stdout";
  if (model.problem == nullptr) {
    EXPECT_EQ(error, "");
    EXPECT_EQ(scene.triangle_count(), model.triangles);
    EXPECT_NO_THROW(scene.validate(path.string()));
  } else {
    EXPECT_NE(error.find(path.string()), std::string::npos) << error;
    EXPECT_NE(error.find(model.problem), std::string::npos) << error;
  }
}

INSTANTIATE_TEST_SUITE_P(Model, BadModels, ::testing::ValuesIn(kBadModels),
                         [](const ::testing::TestParamInfo<BadModel>& param) {
                           std::string name =
                               std::filesystem::path(param.param.path).filename().string();
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

std::filesystem::path scratch(const std::string& name) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("kinray_model_bad_" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  return directory / name;
}

TEST(ModelBadFiles, MissingUnreadableAndUnsupportedFiles) {
  EXPECT_THROW((void)load_model("/nonexistent/robot.gltf"), InputError);
  EXPECT_THROW((void)load_model(std::filesystem::temp_directory_path().string()), InputError);
  const std::filesystem::path garbage = scratch("garbage.gltf");
  std::ofstream(garbage) << "{ this is not json";
  try {
    (void)load_model(garbage.string());
    FAIL() << "garbage must be an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where(), garbage.string());
  }
  const std::filesystem::path unsupported = scratch("notes.kinray-unknown");
  std::ofstream(unsupported) << "hello";
  EXPECT_THROW((void)load_model(unsupported.string()), InputError);
  std::filesystem::remove_all(garbage.parent_path());
}

/// A scene of one triangle under the root, for breaking by hand.
std::unique_ptr<aiScene> triangle_scene() {
  auto scene = std::make_unique<aiScene>();
  scene->mRootNode = new aiNode("root");
  scene->mRootNode->mNumMeshes = 1;
  scene->mRootNode->mMeshes = new unsigned[1]{0};
  scene->mNumMaterials = 1;
  scene->mMaterials = new aiMaterial* [1] { new aiMaterial() };
  aiMesh* mesh = new aiMesh();
  mesh->mNumVertices = 3;
  mesh->mVertices = new aiVector3D[3]{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh->mNumFaces = 1;
  mesh->mFaces = new aiFace[1];
  mesh->mFaces[0].mNumIndices = 3;
  mesh->mFaces[0].mIndices = new unsigned[3]{0, 1, 2};
  scene->mNumMeshes = 1;
  scene->mMeshes = new aiMesh* [1] { mesh };
  return scene;
}

TEST(ModelBadData, NanVerticesAndIndicesOutOfRangeAreInputErrors) {
  EXPECT_NO_THROW((void)convert_model(*triangle_scene(), "good"));
  {
    auto model = triangle_scene();
    model->mMeshes[0]->mVertices[1].y = std::nanf("");
    try {
      (void)convert_model(*model, "nan.obj");
      FAIL();
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("vertex 1 is NaN or infinite"), std::string::npos)
          << error.what();
    }
  }
  {
    auto model = triangle_scene();
    model->mMeshes[0]->mFaces[0].mIndices[2] = 3;
    try {
      (void)convert_model(*model, "index.obj");
      FAIL();
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("out of range"), std::string::npos) << error.what();
    }
  }
  {
    // A NaN in a vertex no triangle uses is harmless: unreferenced vertices are dropped.
    auto model = triangle_scene();
    aiMesh* mesh = model->mMeshes[0];
    aiVector3D* vertices =
        new aiVector3D[4]{mesh->mVertices[0], mesh->mVertices[1], mesh->mVertices[2], {NAN, 0, 0}};
    delete[] mesh->mVertices;
    mesh->mVertices = vertices;
    mesh->mNumVertices = 4;
    const Scene scene = convert_model(*model, "unused-nan");
    EXPECT_EQ(scene.objects.at(0).vertex_count(), 3u);
  }
  {
    // Only lines: nothing to render.
    auto model = triangle_scene();
    model->mMeshes[0]->mFaces[0].mNumIndices = 2;
    const ScopedWarningSink quiet([](const std::string&) {});
    EXPECT_THROW((void)convert_model(*model, "lines"), InputError);
    model->mMeshes[0]->mFaces[0].mNumIndices = 3;
  }
}

/// Adds a string property as assimp stores one (a 32-bit length, the bytes, a zero), but with
/// `claimed` as its length: what a malformed file can leave behind.
void add_string_property(aiMaterial& material, const std::string& text, uint32_t claimed,
                         const char* key, unsigned semantic) {
  std::vector<char> bytes(4 + text.size() + 1, '\0');
  std::memcpy(bytes.data(), &claimed, 4);
  std::memcpy(bytes.data() + 4, text.data(), text.size());
  material.AddBinaryProperty(bytes.data(), unsigned(bytes.size()), key, semantic, 0, aiPTI_String);
}

TEST(ModelBadData, MaterialStringsLongerThanAssimpsFixedStringAreReadWithinTheirBytes) {
  // assimp's own Get(aiString&) copies the claimed length into a 1,024-byte aiString on the
  // caller's stack; fuzz_model_import found a file doing that on CI. The ASan suite checks this.
  auto model = triangle_scene();
  const std::string long_name(3000, 'n');
  add_string_property(*model->mMaterials[0], long_name, uint32_t(long_name.size()), "?mat.name", 0);
  add_string_property(*model->mMaterials[0], "missing.png", 100000, "$tex.file",
                      aiTextureType_DIFFUSE);
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = convert_model(*model, "long-strings");
  ASSERT_EQ(scene.materials.size(), 1u);
  EXPECT_EQ(scene.materials[0].name, long_name);
  // The texture path is cut at the property's end; the file does not exist: a warning, no texture.
  EXPECT_NE(warnings.find("missing.png"), std::string::npos) << warnings;
  EXPECT_EQ(scene.materials[0].texture, -1);
}

/// A text .x cube whose SkinWeights weigh `vertex` (the mesh has 3 vertices).
std::filesystem::path write_x(const std::string& name, unsigned vertex) {
  const std::filesystem::path path = scratch(name);
  const char* identity = "1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0;;\n";
  std::ofstream(path)
      << "xof 0303txt 0032\n"
      << "Frame Root {\n FrameTransformMatrix {\n  " << identity << " }\n"
      << " Frame Bone {\n  FrameTransformMatrix {\n   " << identity << "  }\n }\n"
      << " Mesh Tri {\n  3;\n  0.0;0.0;0.0;,\n  1.0;0.0;0.0;,\n  0.0;1.0;0.0;;\n  1;\n  3;0,1,2;;\n"
      << "  SkinWeights {\n   \"Bone\";\n   2;\n   0,\n   " << vertex << ";\n   1.0,\n   1.0;\n   "
      << identity << "  }\n }\n}\n";
  return path;
}

TEST(ModelBadFiles, TextXSkinWeightsPastTheMeshAreCaughtBeforeAssimp) {
  const std::filesystem::path good = write_x("good.x", 2), bad = write_x("bad.x", 3);
  const Scene scene = load_model(good.string());
  EXPECT_EQ(scene.triangle_count(), 1u);
  try {
    (void)load_model(bad.string());
    FAIL() << "a weight on vertex 3 of 3 must be an InputError";
  } catch (const InputError& error) {
    EXPECT_EQ(error.where(), bad.string());
    EXPECT_NE(std::string(error.what()).find("weighs vertex 3, but the mesh has 3 vertices"),
              std::string::npos)
        << error.what();
  }
  std::filesystem::remove_all(good.parent_path());
}

TEST(ModelBadFiles, PlyCountsTheFileCannotHoldAreCaughtBeforeAssimp) {
  // assimp's PLY reader loops over an element count that no bytes back (elements without
  // properties): it ran into the 300 s import timeout on this file.
  const std::filesystem::path good = scratch("good.ply"), bad = scratch("bad.ply");
  const std::string header =
      "format ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  std::ofstream(good) << "ply\n" << header;
  std::ofstream(bad) << "ply\nelement point 7000000000000\n" << header;
  EXPECT_EQ(load_model(good.string()).triangle_count(), 1u);
  const auto start = std::chrono::steady_clock::now();
  try {
    (void)load_model(bad.string());
    FAIL() << "7e12 elements in 120 bytes must be an InputError";
  } catch (const InputError& error) {
    EXPECT_STREQ(error.what(),
                 (bad.string() + ":2: declares 7000000000000 point elements but no properties "
                                 "for them").c_str());
  }
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  std::filesystem::remove_all(good.parent_path());
}

TEST(ModelGuard, ChildCrashesAndHangsBecomeMessages) {
  EXPECT_EQ(run_in_child([] { return std::string(); }, 10), std::nullopt);
  EXPECT_EQ(run_in_child([] { return std::string("bad header"); }, 10),
            std::optional<std::string>("bad header"));
  const auto crash = run_in_child(
      []() -> std::string {
        std::raise(SIGSEGV);
        return {};
      },
      10);
  ASSERT_TRUE(crash.has_value());
  EXPECT_NE(crash->find("signal"), std::string::npos) << *crash;
  const auto start = std::chrono::steady_clock::now();
  const auto hang = run_in_child(
      []() -> std::string {
        for (;;) pause();
      },
      0.3);
  ASSERT_TRUE(hang.has_value());
  EXPECT_NE(hang->find("did not finish"), std::string::npos) << *hang;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(5));
}

TEST(ModelGuard, TheChildIsForkedOnlyWhenNoThreadOfOursIsWorking) {
  // A loop's body (on a oneTBB thread or on the loop's caller) holds a lock that the child's work
  // needs. Forked while the body held it, the child would wait for it for ever (the body's thread
  // does not exist in the child): it must be forked after the body.
  std::mutex held_by_task;
  std::latch task_holds_it(1);
  std::thread loop([&] {
    parallel_for(2, 2, [&](size_t k) {
      if (k != 0) return;
      const std::lock_guard lock(held_by_task);
      task_holds_it.count_down();
      std::this_thread::sleep_for(std::chrono::milliseconds(300));
    });
  });
  task_holds_it.wait();
  const auto verdict = run_in_child(
      [&] {
        const std::lock_guard lock(held_by_task);
        return std::string();
      },
      5);
  loop.join();
  EXPECT_EQ(verdict, std::nullopt) << *verdict;
}

TEST(ModelGuard, ChildOverItsAddressSpaceLimitFailsWithBadAlloc) {
  if (test::kUnderAddressSanitizer) GTEST_SKIP() << test::kAddressSpaceLimitUnderAsan;
  const auto greedy = run_in_child(
      []() -> std::string {
        std::vector<char> memory(size_t(1) << 32);  // 4 GiB under a 1 GiB limit
        return memory.empty() ? "empty" : "";
      },
      10, size_t(1) << 30);
  ASSERT_TRUE(greedy.has_value());
  EXPECT_NE(greedy->find("bad_alloc"), std::string::npos) << *greedy;
}

}  // namespace
}  // namespace kinray
