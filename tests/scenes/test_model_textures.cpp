// Materials of imported models: base colours, diffuse textures read with OpenCV beside the model or
// embedded in it (sRGB decoded to linear), per-vertex uvs, and the documented repair for a texture
// that cannot be found: a warning and the base colour alone.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "scenes/model_guard.h"
#include "scenes/model_import.h"
#include "scenes/model_textures.h"
#include "scenes/model_tga.h"
#include "scenes/texture_image.h"
#include "tests/scenes/model_test_support.h"
#include "util/warning.h"

namespace kinray {
namespace {

using testing::kTestModels;

/// A unit quad with uvs, in an OBJ whose material names `texture` (empty: none).
std::filesystem::path write_quad(const std::string& texture) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("kinray_model_tex_" + std::to_string(getpid()));
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "quad.obj") << "mtllib quad.mtl\n"
                                           "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                           "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                           "usemtl painted\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n";
  std::ofstream mtl(directory / "quad.mtl");
  mtl << "newmtl painted\nKd 0.5 0.25 1.0\n";
  if (!texture.empty()) mtl << "map_Kd " << texture << "\n";
  return directory / "quad.obj";
}

/// A 2 x 2 image: red, green / blue, sRGB grey 128 (BGR order for OpenCV).
void write_checker(const std::filesystem::path& path) {
  cv::Mat image(2, 2, CV_8UC3);
  image.at<cv::Vec3b>(0, 0) = {0, 0, 255};
  image.at<cv::Vec3b>(0, 1) = {0, 255, 0};
  image.at<cv::Vec3b>(1, 0) = {255, 0, 0};
  image.at<cv::Vec3b>(1, 1) = {128, 128, 128};
  ASSERT_TRUE(cv::imwrite(path.string(), image));
}

TEST(ModelTextures, DiffuseTextureBesideTheModelWithUvs) {
  const std::filesystem::path obj = write_quad("checker.png");
  write_checker(obj.parent_path() / "checker.png");
  const Scene scene = load_model(obj.string());
  std::filesystem::remove_all(obj.parent_path());
  ASSERT_EQ(scene.objects.size(), 1u);
  const Material& material = scene.materials.at(scene.objects[0].material);
  EXPECT_TRUE(material.base_color.isApprox(Color(0.5f, 0.25f, 1.0f)));
  ASSERT_EQ(material.texture, 0);
  const Texture& texture = scene.textures.at(0);
  ASSERT_EQ(texture.width, 2);
  ASSERT_EQ(texture.height, 2);
  EXPECT_TRUE(texture.texels[0].isApprox(Color(1, 0, 0)));  // row 0 is the top
  EXPECT_TRUE(texture.texels[1].isApprox(Color(0, 1, 0)));
  EXPECT_TRUE(texture.texels[2].isApprox(Color(0, 0, 1)));
  // sRGB 128 is linear ((128/255 + 0.055) / 1.055)^2.4 = 0.2158605.
  EXPECT_NEAR(texture.texels[3].x(), 0.2158605, 1e-6);
  EXPECT_NEAR(srgb_to_linear(128), 0.2158605, 1e-6);
  EXPECT_EQ(srgb_to_linear(0), 0.0f);
  EXPECT_EQ(srgb_to_linear(255), 1.0f);
  // Every vertex keeps its uv: the corner at (1, 1, 0) has uv (1, 1).
  const Object& quad = scene.objects[0];
  ASSERT_EQ(quad.uvs.size(), quad.vertex_count());
  for (uint32_t v = 0; v < quad.vertex_count(); ++v) {
    const Vec3& p = quad.key_positions[0][v];
    EXPECT_NEAR(quad.uvs[v].x(), p.x(), 1e-6);
    EXPECT_NEAR(quad.uvs[v].y(), p.y(), 1e-6);
  }
}

TEST(ModelTextures, AbsolutePathOfTheAuthorsMachineIsLookedUpBesideTheModel) {
  const std::filesystem::path obj = write_quad("C:\\Users\\artist\\maps\\checker.png");
  write_checker(obj.parent_path() / "checker.png");
  const Scene scene = load_model(obj.string());
  std::filesystem::remove_all(obj.parent_path());
  EXPECT_EQ(scene.textures.size(), 1u);
  EXPECT_EQ(scene.materials.at(scene.objects.at(0).material).texture, 0);
}

TEST(ModelTextures, MissingTextureIsAWarningAndTheBaseColour) {
  const std::filesystem::path obj = write_quad("missing.png");
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = load_model(obj.string());
  std::filesystem::remove_all(obj.parent_path());
  EXPECT_NE(warnings.find("missing.png"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find("quad.obj"), std::string::npos) << warnings;
  EXPECT_TRUE(scene.textures.empty());
  const Material& material = scene.materials.at(scene.objects.at(0).material);
  EXPECT_EQ(material.texture, -1);
  EXPECT_TRUE(material.base_color.isApprox(Color(0.5f, 0.25f, 1.0f)));
  EXPECT_NO_THROW(scene.validate(obj.string()));
}

TEST(ModelTextures, UndecodableTextureIsAWarningAndTheBaseColour) {
  const std::filesystem::path obj = write_quad("broken.png");
  std::ofstream(obj.parent_path() / "broken.png") << "not a png at all";
  std::string warnings;
  const ScopedWarningSink collect([&](const std::string& line) { warnings += line + "\n"; });
  const Scene scene = load_model(obj.string());
  std::filesystem::remove_all(obj.parent_path());
  EXPECT_NE(warnings.find("could not be decoded"), std::string::npos) << warnings;
  EXPECT_EQ(scene.materials.at(scene.objects.at(0).material).texture, -1);
}

/// The Cesium logo box as a .gltf beside its png, as a .glb holding the png ("*0"), and as a
/// .gltf with a data: URI: all three give the texture OpenCV reads from the png.
TEST(ModelTextures, EmbeddedTexturesMatchTheFileTheyWereMadeFrom) {
  const std::filesystem::path png = kTestModels / "glTF2/BoxTextured-glTF/CesiumLogoFlat.png";
  if (!std::filesystem::exists(png)) GTEST_SKIP() << png << " is not installed";
  const cv::Mat reference = cv::imread(png.string(), cv::IMREAD_COLOR);
  ASSERT_FALSE(reference.empty());
  for (const char* model :
       {"glTF2/BoxTextured-glTF/BoxTextured.gltf", "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb",
        "glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf"}) {
    const Scene scene = load_model((kTestModels / model).string());
    ASSERT_EQ(scene.textures.size(), 1u) << model;
    const Texture& texture = scene.textures[0];
    EXPECT_EQ(texture.width, reference.cols) << model;
    EXPECT_EQ(texture.height, reference.rows) << model;
    for (int y = 0; y < reference.rows; y += 37)
      for (int x = 0; x < reference.cols; x += 41) {
        const cv::Vec3b bgr = reference.at<cv::Vec3b>(y, x);
        const Color expected(srgb_to_linear(bgr[2]), srgb_to_linear(bgr[1]),
                             srgb_to_linear(bgr[0]));
        EXPECT_TRUE(
            texture.texels[size_t(y) * size_t(texture.width) + size_t(x)].isApprox(expected, 1e-6f))
            << model;
      }
    for (const Object& object : scene.objects) {
      EXPECT_EQ(object.uvs.size(), object.vertex_count()) << model;
      EXPECT_GE(scene.materials.at(object.material).texture, 0) << model;
    }
  }
}

/// The checker of write_checker as TGA bytes: uncompressed 24-bit rows from the bottom (the
/// default origin), or run-length encoded 32-bit rows from the top.
std::vector<uint8_t> checker_tga(bool run_length) {
  std::vector<uint8_t> bytes = {0,
                                0,
                                uint8_t(run_length ? 10 : 2),
                                0,
                                0,
                                0,
                                0,
                                0,
                                0,
                                0,
                                0,
                                0,
                                2,
                                0,
                                2,
                                0,
                                uint8_t(run_length ? 32 : 24),
                                uint8_t(run_length ? 0x28 : 0)};
  if (!run_length) {
    // bottom row first: blue, grey; then red, green (BGR)
    for (uint8_t v : {255, 0, 0, 128, 128, 128, 0, 0, 255, 0, 255, 0}) bytes.push_back(v);
  } else {
    // top row: a raw packet of red, green; bottom row: a raw packet of blue, then grey as a run of
    // 1
    for (uint8_t v :
         {1, 0, 0, 255, 255, 0, 255, 0, 255, 0, 255, 0, 0, 255, 0x80, 128, 128, 128, 255})
      bytes.push_back(v);
  }
  return bytes;
}

// A header of 65535 x 65535 true-colour pixels over a few bytes of data (found by reading the
// decoder for its fuzz harness; tests/fuzz/regressions/tga/ keeps both inputs): decoding used to
// allocate the whole 17 GB image before finding the data short. In a child whose address space
// is only 512 MiB above this process's, a decoder that allocates first fails with bad_alloc.
TEST(ModelTextures, TgaHeaderLargerThanItsDataIsRefusedBeforeAllocating) {
  for (bool run_length : {false, true}) {
    std::vector<uint8_t> bytes = checker_tga(run_length);
    bytes[12] = bytes[13] = bytes[14] = bytes[15] = 0xff;
    size_t used_pages = 0;
    std::ifstream("/proc/self/statm") >> used_pages;
    const size_t limit = used_pages * size_t(sysconf(_SC_PAGESIZE)) + (size_t(512) << 20);
    const std::optional<std::string> failure = run_in_child(
        [&] { return decode_tga(bytes).empty() ? std::string() : std::string("decoded"); }, 60,
        limit);
    EXPECT_EQ(failure, std::nullopt) << (run_length ? "run-length" : "uncompressed");
  }
}

TEST(ModelTextures, TgaWhichOpenCvLacksIsDecoded) {
  for (bool run_length : {false, true}) {
    const cv::Mat image = decode_tga(checker_tga(run_length));
    ASSERT_EQ(image.rows, 2);
    ASSERT_EQ(image.cols, 2);
    EXPECT_EQ(image.at<cv::Vec3b>(0, 0), cv::Vec3b(0, 0, 255)) << run_length;
    EXPECT_EQ(image.at<cv::Vec3b>(0, 1), cv::Vec3b(0, 255, 0)) << run_length;
    EXPECT_EQ(image.at<cv::Vec3b>(1, 0), cv::Vec3b(255, 0, 0)) << run_length;
    EXPECT_EQ(image.at<cv::Vec3b>(1, 1), cv::Vec3b(128, 128, 128)) << run_length;
  }
  std::vector<uint8_t> truncated = checker_tga(true);
  truncated.resize(truncated.size() - 2);
  EXPECT_TRUE(decode_tga(truncated).empty());
  EXPECT_TRUE(decode_tga(std::vector<uint8_t>{1, 2, 3}).empty());

  const std::filesystem::path obj = write_quad("checker.tga");
  const std::vector<uint8_t> bytes = checker_tga(false);
  std::ofstream(obj.parent_path() / "checker.tga", std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  const Scene scene = load_model(obj.string());
  std::filesystem::remove_all(obj.parent_path());
  ASSERT_EQ(scene.textures.size(), 1u);
  EXPECT_TRUE(scene.textures[0].texels[0].isApprox(Color(1, 0, 0)));
  EXPECT_NEAR(scene.textures[0].texels[3].x(), 0.2158605, 1e-6);
}

TEST(ModelTextures, TestModelsWithTgaAndEmbeddedSkins) {
  const std::filesystem::path duck =
      kTestModels / "Collada/duck.dae";  // names duckCM.tga, 512 x 512
  const std::filesystem::path mdl =
      kTestModels / "MDL/MDL (HL1)/alpha_test.mdl";  // raw texels inside
  if (!std::filesystem::exists(duck) || !std::filesystem::exists(mdl))
    GTEST_SKIP() << "assimp-testmodels not installed";
  const Scene duck_scene = load_model(duck.string());
  ASSERT_EQ(duck_scene.textures.size(), 1u);
  EXPECT_EQ(duck_scene.textures[0].width, 512);
  EXPECT_EQ(duck_scene.textures[0].height, 512);
  EXPECT_EQ(duck_scene.objects.at(0).uvs.size(), duck_scene.objects[0].vertex_count());
  const Scene mdl_scene = load_model(mdl.string());
  ASSERT_EQ(mdl_scene.textures.size(), 1u);
  EXPECT_GT(mdl_scene.textures[0].width, 0);
  EXPECT_EQ(mdl_scene.textures[0].texels.size(),
            size_t(mdl_scene.textures[0].width) * size_t(mdl_scene.textures[0].height));
}

}  // namespace
}  // namespace kinray
