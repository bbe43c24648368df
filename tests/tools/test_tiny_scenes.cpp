// Every command on the smallest scenes a user can write: one triangle, static or moving, two
// coincident ones, a degenerate one beside a real one, one static and one moving object. Trees
// of one leaf and lists of one pair are where a kinetic structure's boundary cases live (a
// one-triangle mesh once crashed the separation list's self pair and `render --contacts`).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

struct TinyScene {
  const char* name;
  const char* objects;  ///< the scene file's "objects" array
};

// A triangle that tilts through the plane z = 0 over the shot, so that it meets a static one.
constexpr const char* kTilting =
    R"({"kind": "mesh", "name": "tilting", "triangles": [[0, 1, 2]],
        "keys": [{"time": 0, "vertices": [[-1, -1, 0.5], [1, -1, 0.5], [0, 1, -0.5]]},
                 {"time": 1, "vertices": [[-1, -1, -0.5], [1, -1, -0.5], [0, 1, 0.5]]}]})";
constexpr const char* kStatic =
    R"({"kind": "mesh", "name": "static", "vertices": [[-2, -0.5, 0], [2, -0.5, 0], [0, 0.8, 0]],
        "triangles": [[0, 1, 2]]})";

const TinyScene kScenes[] = {
    {"one_moving_triangle", "[KT]"},
    {"one_static_triangle", "[KS]"},
    {"one_static_one_moving", "[KS, KT]"},
    {"two_coincident_moving",
     R"([{"kind": "mesh", "name": "twins", "triangles": [[0, 1, 2], [0, 1, 2]],
          "keys": [{"time": 0, "vertices": [[-1, -1, 0], [1, -1, 0], [0, 1, 0]]},
                   {"time": 1, "vertices": [[-1, -1, 1], [1, -1, 0], [0, 1, -1]]}]}])"},
    {"degenerate_beside_a_triangle",
     R"([{"kind": "mesh", "name": "sliver", "triangles": [[0, 1, 2], [3, 4, 5]],
          "keys": [{"time": 0, "vertices": [[-1, 0, 0], [0, 0, 0], [1, 0, 0],
                                            [-1, -1, 0.2], [1, -1, 0.2], [0, 1, 0.2]]},
                   {"time": 1, "vertices": [[-1, 0.5, 0], [0, 0.5, 0], [1, 0.5, 0],
                                            [-1, -1, -0.2], [1, -1, -0.2], [0, 1, -0.2]]}]}])"},
    {"three_triangles_one_mesh",
     R"([{"kind": "mesh", "name": "fan", "triangles": [[0, 1, 2], [0, 2, 3], [0, 3, 1]],
          "keys": [{"time": 0, "vertices": [[0, 0, 0.3], [-1, -1, 0], [1, -1, 0], [0, 1, 0]]},
                   {"time": 1, "vertices": [[0, 0, -0.3], [-1, -1, 0.1], [1, -1, 0], [0, 1, -0.1]]}]}])"},
};

std::string with_objects(const std::string& objects) {
  std::string text = objects;
  for (const auto& [token, object] : {std::pair{"KT", kTilting}, std::pair{"KS", kStatic}})
    for (size_t at = text.find(token); at != std::string::npos; at = text.find(token))
      text.replace(at, 2, object);
  return R"({"shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"position": [0.3, 0.2, 5], "look_at": [0, 0, 0], "fov_y": 45}]},
    "objects": )" +
         text + "}";
}

class TinyScenes : public test::CommandTest {
 protected:
  /// Writes the scene file and returns its path.
  std::string scene_file(const TinyScene& scene) {
    const std::string file = path(std::string(scene.name) + ".json");
    std::ofstream(file) << with_objects(scene.objects);
    return file;
  }
  /// Runs `kinray ARGS` and expects it to succeed.
  void succeeds(const std::string& args) {
    SCOPED_TRACE(args);
    const test::CommandRun run = kinray(args);
    EXPECT_EQ(run.status, 0) << run.err;
  }
  /// The contacts `collide` reports, without their points.
  nlohmann::json contacts(const std::string& args) {
    const std::string json = path("contacts.json");
    succeeds("collide " + args + " -q --json '" + json + "'");
    nlohmann::json out = nlohmann::json::array();
    if (!fs::exists(json)) return out;
    const nlohmann::json report = nlohmann::json::parse(test::read_text(json));
    for (nlohmann::json c : report["contacts"]) {
      c.erase("point");
      out.push_back(c);
    }
    fs::remove(json);
    return out;
  }
};

TEST_F(TinyScenes, EveryBackendRendersThemWithAndWithoutContacts) {
  for (const TinyScene& scene : kScenes) {
    SCOPED_TRACE(scene.name);
    const std::string file = "'" + scene_file(scene) + "'";
    succeeds("info " + file);
    for (const char* backend : {"kinetic", "embree", "osmesa"}) {
      const std::string out = path(std::string(scene.name) + "_" + backend);
      succeeds("render " + file + " --backend " + std::string(backend) +
               " --size 24x16 --frames 3 --contacts -q --out '" + out + "'");
      EXPECT_TRUE(fs::exists(fs::path(out) / "frame_00002.png"));
    }
    succeeds("render " + file + " --size 24x16 --frames 3 --audit -q --out '" + path("audit") +
             "'");
    succeeds("render " + file + " --size 24x16 --frames 2 --light point:1,2,4 -q --out '" +
             path("lit") + "'");
    succeeds("render " + file + " --size 24x16 --frames 2 --shutter 0.5 -q --out '" + path("blur") +
             "'");
    succeeds("diff " + file + " --size 24x16 --frames 3 -q");
  }
}

TEST_F(TinyScenes, EveryContactStructureFindsTheSameContacts) {
  size_t with_contacts = 0;
  for (const TinyScene& scene : kScenes) {
    SCOPED_TRACE(scene.name);
    const std::string file = "'" + scene_file(scene) + "'";
    for (const char* self : {"", " --self"}) {
      const nlohmann::json brute = contacts(file + self + " --structure brute");
      EXPECT_EQ(contacts(file + self + " --structure swept"), brute);
      EXPECT_EQ(contacts(file + self + " --structure ksl --audit"), brute);
      EXPECT_EQ(contacts(file + self + " --structure ksl --checks 5"), brute);
      with_contacts += !brute.empty();
    }
  }
  // the tilting triangle meets the static one, the fan's apex passes through its base plane
  EXPECT_GE(with_contacts, 2u);
}

}  // namespace
}  // namespace kinray
