// Coordinates the float references cannot trace are bad input named at load time, so `diff`
// cannot pass a scene that Embree and OSMesa do not see; a glTF whose buffer is garbage is
// refused instead of rendering blank frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

class CliVerdicts : public test::CommandTest {};

/// A one-triangle scene whose third vertex is at (0, `far`, 3).
std::string scene_with_vertex_at(const std::string& far) {
  return R"({"shot": {"begin": 0, "end": 1},
  "camera": {"keys": [{"time": 0, "position": [0, 0, -5], "look_at": [0, 0, 0], "fov_y": 45}]},
  "objects": [{"kind": "mesh", "triangles": [[0, 1, 2]],
    "keys": [{"time": 0, "vertices": [[-1, -1, 0], [1, -1, 0], [0, )" +
         far + R"(, 3]]}]}]})";
}

TEST_F(CliVerdicts, CoordinatesBeyondWhatFloatCanTraceAreBadInput) {
  for (const char* far : {"1e300", "1e30", "2e15"}) {
    SCOPED_TRACE(far);
    std::ofstream(path("far.json")) << scene_with_vertex_at(far);
    for (const std::string command : {"render", "diff", "info"}) {
      const std::string flags = command == "info" ? ""
                                : command == "diff"
                                    ? " --size 32x32 --frames 1 -q"
                                    : " --size 32x32 --frames 1 -q --out '" + path("f") + "'";
      const test::CommandRun run = kinray(command + " '" + path("far.json") + "'" + flags);
      EXPECT_EQ(run.status, 2) << command << ": " << run.err;
      EXPECT_NE(run.err.find("far.json: object 0"), std::string::npos) << run.err;
      EXPECT_NE(run.err.find("vertex 2 at key 0 has a coordinate beyond +-1e15"), std::string::npos)
          << command << ": " << run.err;
    }
  }
  EXPECT_FALSE(fs::exists(path("f")));
  std::ofstream(path("near.json")) << scene_with_vertex_at("1e14");
  const test::CommandRun run = kinray("info '" + path("near.json") + "'");
  EXPECT_EQ(run.status, 0) << run.err;
}

TEST_F(CliVerdicts, AModelCoordinateBeyondFloatIsRefusedSayingSo) {
  // An OBJ's coordinates are read before assimp (which reads positions as float, and 1e300 as
  // infinity): the line is named. 1e999 is no double at all and stays assimp's: infinity.
  const std::pair<const char*, const char*> cases[] = {
      {"1e300", ":3: coordinate y = 1e+300 lies beyond +-1e15"},
      {"1e30", ":3: coordinate y = 1e+30 lies beyond +-1e15"},
      {"1e999", ": mesh 0 'defaultobject': vertex 2 is NaN or infinite as a float"}};
  for (const auto& [far, problem] : cases) {
    SCOPED_TRACE(far);
    std::ofstream(path("far.obj")) << "v -1 -1 0\nv 1 -1 0\nv 0 " << far << " 3\nf 1 2 3\n";
    const test::CommandRun run = kinray("render '" + path("far.obj") +
                                        "' --size 32x32 --frames 1 -q --out '" + path("f") + "'");
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_EQ(run.err.rfind("kinray: error: " + path("far.obj") + ":", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(problem), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  EXPECT_FALSE(fs::exists(path("f")));
}

std::string base64(const std::vector<uint8_t>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = uint32_t(bytes[i]) << 16 |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
    text += digits[n >> 18 & 63];
    text += digits[n >> 12 & 63];
    text += i + 1 < bytes.size() ? digits[n >> 6 & 63] : '=';
    text += i + 2 < bytes.size() ? digits[n & 63] : '=';
  }
  return text;
}

TEST_F(CliVerdicts, AGltfWhoseBufferIsGarbageIsRefused) {
  // Three float positions, one of them garbage of the kind a corrupt buffer holds.
  const float positions[9] = {-1, -1, 0, 1, -1, 0, 0, 1.7e38f, 0};
  std::vector<uint8_t> bytes(sizeof positions);
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::ofstream(path("garbage.gltf")) << R"({"asset": {"version": "2.0"}, "scene": 0,
    "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" +
                                             base64(bytes) + R"("}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [-1, -1, 0], "max": [1, 1, 0]}]})";
  const test::CommandRun run = kinray("render '" + path("garbage.gltf") +
                                      "' --size 32x32 --frames 1 -q --out '" + path("f") + "'");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("garbage.gltf"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("beyond +-1e15"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(path("f")));
}

TEST_F(CliVerdicts, ASharedGltfWithItsPositionBufferCorruptedIsRefused) {
  // A copy of a shared glTF whose POSITION bytes are overwritten with 0xDEADBEEF (as floats about
  // -1.2e29, and 1.2e31 after the node's scale): finite garbage, far beyond what float traces.
  const fs::path source =
      fs::path(KINRAY_SHARED_DIR) / "data/models/glTF2/AnimatedMorphSphere/glTF";
  if (!fs::exists(source / "AnimatedMorphSphere.gltf"))
    GTEST_SKIP() << "no " << source << " (the shared folder's models)";
  for (const char* name : {"AnimatedMorphSphere.gltf", "AnimatedMorphSphere.bin"})
    fs::copy_file(source / name, path(name));
  const nlohmann::json gltf =
      nlohmann::json::parse(test::read_text(path("AnimatedMorphSphere.gltf")));
  const nlohmann::json& accessor =
      gltf["accessors"][gltf["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<size_t>()];
  const nlohmann::json& view = gltf["bufferViews"][accessor["bufferView"].get<size_t>()];
  const size_t offset =
      view.value("byteOffset", size_t(0)) + accessor.value("byteOffset", size_t(0));
  const size_t length = 12 * accessor["count"].get<size_t>();
  {
    std::fstream bin(path("AnimatedMorphSphere.bin"),
                     std::ios::in | std::ios::out | std::ios::binary);
    bin.seekp(std::streamoff(offset));
    for (size_t i = 0; i < length; i += 4) bin.write("\xef\xbe\xad\xde", 4);
    ASSERT_TRUE(bin.good());
  }
  const std::string model = "'" + path("AnimatedMorphSphere.gltf") + "'";
  for (const std::string& args :
       {"render " + model + " --size 32x32 --frames 1 -q --out '" + path("f") + "'",
        "diff " + model + " --size 32x32 --frames 1 -q --json '" + path("d.json") + "'",
        "info " + model}) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_EQ(run.out, "");
    // One line, naming the file, the object and the vertex, and saying why.
    EXPECT_EQ(run.err.rfind("kinray: error: " + path("AnimatedMorphSphere.gltf") + ": object 0", 0),
              0u)
        << run.err;
    EXPECT_NE(run.err.find("vertex 0 at key 0 has a coordinate beyond +-1e15"), std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find("which the float references cannot trace"), std::string::npos)
        << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
  }
  EXPECT_FALSE(fs::exists(path("f")));
  EXPECT_FALSE(fs::exists(path("d.json")));
}

}  // namespace
}  // namespace kinray
