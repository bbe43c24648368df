// AFF (BART) files written on the spot and read back: meshes with texture coordinates, includes
// relative to the including file, static and animated transforms against matrices computed here,
// the camera's keyframes, tessellated primitives, CRLF line ends, a missing texture (a warning),
// and malformed files, each one InputError naming the file, the line and the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "scenes/aff_parser.h"
#include "scenes/aff_scene.h"
#include "scenes/aff_tessellate.h"
#include "scenes/scene_loader.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// A fresh folder for one test's files.
fs::path scratch(const std::string& name) {
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_aff_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  fs::create_directories(folder);
  return folder;
}

void write(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

const char* kView =
    "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.1\nresolution 320 240\n";

/// Four keys of a translation along x at 1 unit per second: the Catmull-Rom curve is that line.
const char* kSlide =
    "k slide\n{\n transl 4\n -1 -1 0 0 0 0 0\n 0 0 0 0 0 0 0\n 2 2 0 0 0 0 0\n 3 3 0 0 0 0 0\n}\n";

TEST(AffParser, MeshIncludesTransformsAndAnimation) {
  const fs::path folder = scratch("mesh");
  write(folder / "parts" / "quad.aff",
        "fm 0 0 0  0.5 0.25 1  0 0 0  1 0 1\n"
        "m\n vertices 4\n 0 0 0\n 1 0 0\n 1 1 0\n 0 1 0\n"
        " normals 1\n 0 0 1\n"
        " texturecoords 2 tex.ppm\n 0 0\n 1 1\n"
        " triangles 2\n 0 1 2  0 0 0  0 1 1\n 0 2 3  0 0 0  1 1 0\n");
  write(folder / "parts" / "tex.ppm", "P3\n2 1\n255\n255 0 0  0 0 255\n");
  write(folder / "scene.aff", std::string(kView) + "a 0 2 5\n" +
                                  "xs 2 2 2  0 0 1 90  10 0 0\n{\n i 0 parts/quad.aff\n}\n"
                                  "x slide\n{\n i 0 parts/quad.aff\n}\n" +
                                  kSlide);
  const Scene scene = load_scene((folder / "scene.aff").string());
  ASSERT_EQ(scene.objects.size(), 2u);
  EXPECT_EQ(scene.image_width, 320);
  EXPECT_EQ(scene.image_height, 240);
  EXPECT_EQ(scene.frame_count, 5);
  EXPECT_EQ(scene.time_begin, 0);
  EXPECT_EQ(scene.time_end, 2);
  // (v, uv) corners: v0 with uv0 and uv1 ... 5 distinct corners.
  const Object& fixed = scene.objects[0];
  EXPECT_EQ(fixed.vertex_count(), 5u);
  EXPECT_EQ(fixed.key_count(), 1u);
  const Material& material = scene.materials[fixed.material];
  EXPECT_EQ(material.base_color, Color(0.5f, 0.25f, 1.0f));
  ASSERT_GE(material.texture, 0);
  EXPECT_EQ(scene.textures[size_t(material.texture)].width, 2);
  // Vertex (1, 1, 0) scaled by 2, turned 90 degrees about z, moved by (10, 0, 0): (8, 2, 0).
  bool found = false;
  for (const Vec3& p : fixed.key_positions[0]) found |= (p - Vec3(8, 2, 0)).norm() < 1e-12;
  EXPECT_TRUE(found);
  // The animated copy: sampled at the five frame times, x moved by t.
  const Object& sliding = scene.objects[1];
  ASSERT_EQ(sliding.key_times, (std::vector<double>{0, 0.5, 1, 1.5, 2}));
  for (size_t k = 0; k < sliding.key_count(); ++k)
    for (size_t v = 0; v < sliding.vertex_count(); ++v)
      EXPECT_NEAR((sliding.key_position(k, uint32_t(v)) - sliding.key_position(0, uint32_t(v)) -
                   Vec3(sliding.key_times[k], 0, 0))
                      .norm(),
                  0, 1e-12)
          << k;
  EXPECT_NEAR((sliding.position(1, 1.25) - sliding.position(1, 0) - Vec3(1.25, 0, 0)).norm(), 0,
              1e-12);
  // --keyrate: every 1/3 s from the start, plus the end.
  const Scene resampled = load_aff(folder / "scene.aff", 3);
  EXPECT_EQ(resampled.objects[1].key_times,
            (std::vector<double>{0, 1.0 / 3, 2.0 / 3, 1, 4.0 / 3, 5.0 / 3, 2}));
}

TEST(AffParser, CameraKeyframesAndCrlf) {
  const fs::path folder = scratch("camera");
  std::string text =
      std::string(kView) + "l 1 2 3\nl 4 5 6 0.5 0.5 0.5\nb 0.1 0.2 0.3\nam 1 1 1\n" +
      "a 0 1 3\ns 0 0 0 1\n"
      "k camera\n{\n transl 4\n -1 0 0 9 0 0 0\n 0 0 0 10 0 0 0\n 1 0 0 11 0 0 0\n 2 0 0 12 0 0 0\n"
      " rot 4\n -1 0 1 0 90 0 0 0\n 0 0 1 0 90 0 0 0\n 1 0 1 0 90 0 0 0\n 2 0 1 0 90 0 0 0\n}\n";
  std::string crlf;
  for (char c : text) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  write(folder / "lf.aff", text);
  write(folder / "crlf.aff", crlf);
  const Scene lf = load_aff(folder / "lf.aff"), with_cr = load_aff(folder / "crlf.aff");
  ASSERT_EQ(lf.camera.keys.size(), 3u);
  ASSERT_EQ(with_cr.camera.keys.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const CameraKey& key = lf.camera.keys[k];
    EXPECT_EQ(key.position, with_cr.camera.keys[k].position);
    EXPECT_NEAR((key.position - Vec3(0, 0, 10 + 0.5 * double(k))).norm(), 0, 1e-12);
    // BART looks along -z of the rotation: 90 degrees about y turns -z into -x.
    EXPECT_NEAR((key.orientation * Vec3(0, 0, -1) - Vec3(-1, 0, 0)).norm(), 0,
                1e-12);  // looks down -z
    EXPECT_NEAR((key.orientation * Vec3(0, 1, 0) - Vec3(0, 1, 0)).norm(), 0, 1e-12);
    EXPECT_EQ(key.fov_y_degrees, 40);
  }
  ASSERT_EQ(lf.lights.size(), 2u);
  EXPECT_EQ(lf.lights[0].color, Color(1, 1, 1));
  EXPECT_EQ(lf.lights[1].position, Vec3(4, 5, 6));
  EXPECT_EQ(lf.lights[1].color, Color(0.5f, 0.5f, 0.5f));
  EXPECT_EQ(lf.triangle_count(), with_cr.triangle_count());
}

TEST(AffParser, TessellatedPrimitivesLieOnTheirSurfaces) {
  const fs::path folder = scratch("primitives");
  write(folder / "s.aff", std::string(kView) +
                              "s 1 2 3 2\nc\n0 0 0 1\n0 0 4 0.5\np 4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
                              "pp 3\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\ntt tex.ppm\n0 0 0 0 "
                              "0\n1 0 0 1 0\n0 1 0 0 1\n");
  const Scene scene = load_aff(folder / "s.aff");  // tex.ppm is missing: a warning
  ASSERT_EQ(scene.objects.size(), 5u);
  EXPECT_EQ(scene.objects[0].triangles.size(), size_t(2 * kSphereSegments * (kSphereRings - 1)));
  for (const Vec3& p : scene.objects[0].key_positions[0])
    EXPECT_NEAR((p - Vec3(1, 2, 3)).norm(), 2, 1e-12);
  EXPECT_EQ(scene.objects[1].triangles.size(), size_t(2 * kConeSegments));
  for (const Vec3& p : scene.objects[1].key_positions[0])
    EXPECT_NEAR(std::hypot(p.x(), p.y()), 1 - p.z() / 8, 1e-12);  // radius 1 at z=0, 0.5 at z=4
  EXPECT_EQ(scene.objects[2].triangles.size(), 2u);
  EXPECT_EQ(scene.objects[3].triangles.size(), 1u);
  EXPECT_EQ(scene.objects[4].uvs.size(), 3u);
  EXPECT_EQ(scene.materials[scene.objects[4].material].texture, -1);
  const AffDocument document = parse_aff(folder / "s.aff");
  ASSERT_EQ(document.warnings.size(), 1u);
  EXPECT_NE(document.warnings[0].find("s.aff:21: texture"), std::string::npos)
      << document.warnings[0];
}

TEST(AffParser, AnimatedTrianglesMoveLinearlyBetweenTheirKeys) {
  const fs::path folder = scratch("tpa");
  write(folder / "t.aff", std::string(kView) +
                              "a 0 2 3\ntpa 2\n0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n"
                              "2\n0 0 2 0 0 1\n1 0 2 0 0 1\n0 1 2 0 0 1\n");
  const Scene scene = load_aff(folder / "t.aff");
  ASSERT_EQ(scene.objects.size(), 1u);
  EXPECT_EQ(scene.objects[0].key_times, (std::vector<double>{0, 2}));
  EXPECT_NEAR((scene.objects[0].position(2, 0.5) - Vec3(0, 1, 0.5)).norm(), 0, 1e-12);
}

struct Malformed {
  const char* name;
  std::string text;
  const char* where;    ///< ":line" expected in the message
  const char* problem;  ///< a piece of the message
};

TEST(AffParser, MalformedFilesNameFileLineAndProblem) {
  const std::string v = kView;  // 7 lines
  const std::vector<Malformed> cases = {
      {"number", v + "b 1 x 0\n", ":8", "expected the background colour (a number), got 'x'"},
      {"unknown", v + "\nq 1 2\n", ":9", "unknown element 'q'"},
      {"index", v + "m\nvertices 3\n0 0 0\n1 0 0\n0 1 0\ntriangles 1\n0 1 3\n", ":14",
       "a vertex index 3 is out of range"},
      {"section", v + "m\nvertices 1\n0 0 0\nfaces 1\n", ":11", "unknown mesh section 'faces'"},
      {"truncated", v + "m\nvertices 2\n0 0 0\n1 1\n", ":11", "got the end of the file"},
      {"unclosed", v + "xs 1 1 1 0 1 0 0 0 0 0\n{\ns 0 0 0 1\n", ":10",
       "expected '}' (closing a transform)"},
      {"stray brace", v + "}\n", ":8", "'}' without a matching '{'"},
      {"few keys", v + "k a\n{\ntransl 3\n0 0 0 0 0 0 0\n1 0 0 0 0 0 0\n2 0 0 0 0 0 0\n}\n", ":10",
       "at least 4 keys"},
      {"equal times",
       v + "k a\n{\nscale 4\n0 1 1 1 0 0 0\n1 1 1 1 0 0 0\n1 1 1 1 0 0 0\n1 1 1 1 0 0 0\n}\n",
       ":14", "three scale keys in a row share the time"},
      {"no include", v + "i 0 missing.aff\n", ":8", "no such file"},
      {"cycle", v + "i 0 cycle.aff\n", ":8", "an include cycle?"},
      {"view", "v\nfrom 0 0 0\nat 0 0 0\nup 0 1 0\nangle 40\nhither 1\nresolution 8 8\n", ":7",
       "from and at coincide"},
      {"angle", "v\nfrom 0 0 1\nat 0 0 0\nup 0 1 0\nangle 190\nhither 1\nresolution 8 8\n", ":5",
       "(0, 180)"},
      {"range", v + "a 2 1 10\n", ":8", "must end after it starts"},
      {"frames", v + "a 0 1 -3\n", ":8", "frame count must lie in"},
      {"cone", v + "c 0 0 0 1 0 0 0 1\n", ":8", "base and apex coincide"},
      {"polygon", v + "p 2\n0 0 0\n1 1 1\n", ":8", "vertex count must lie in"},
      {"tpa", v + "a 0 1 2\ntpa 2\n1\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n0.5\n", ":14",
       "must increase"},
      {"visibility", v + "k a\n{\nvisibility 1\n0 1\n}\n", ":10",
       "visibility keyframes are not supported"},
      {"no view", "s 0 0 0 1\n", "no view", "no view"},
      {"huge count", v + "m\nvertices 99999999999\n", ":9", "the vertex count must lie in"},
  };
  for (const Malformed& c : cases) {
    const fs::path folder = scratch("bad");
    const fs::path file = folder / (std::string(c.name) + ".aff");
    write(file, c.text);
    if (std::string(c.name) == "cycle") write(folder / "cycle.aff", "i 0 cycle.aff\n");
    try {
      (void)load_aff(file);
      ADD_FAILURE() << c.name << ": no error";
    } catch (const InputError& error) {
      const std::string message = error.what();
      EXPECT_EQ(message.find('\n'), std::string::npos) << c.name;
      if (std::string(c.name) != "no view" && std::string(c.name) != "cycle") {
        EXPECT_EQ(message.rfind(file.string() + c.where + ": ", 0), 0u)
            << c.name << ": " << message;
      }
      EXPECT_NE(message.find(c.problem), std::string::npos) << c.name << ": " << message;
    }
  }
}

TEST(AffParser, MalformedTextureIsAnErrorNamingIt) {
  const fs::path folder = scratch("ppm");
  write(folder / "bad.ppm", "P6\n4 4\n255\nabc");
  write(folder / "t.aff", std::string(kView) + "tt bad.ppm\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n");
  try {
    (void)load_aff(folder / "t.aff");
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_EQ(std::string(error.what()), (folder / "t.aff").string() + ":8: texture '" +
                                             (folder / "bad.ppm").string() +
                                             "': the pixel data is truncated");
  }
}

}  // namespace
}  // namespace kinray
