// `kinray collide`: a contact at a known time, identical contact sets from swept volumes and brute
// force on the collision scenes, time order, and bad input.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

class CollideCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_collide_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
             std::to_string(getpid()));  // two suites at once (two checkouts) do not share it
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  nlohmann::json collide(const std::string& args) {
    const fs::path json = m_dir / "contacts.json";
    const test::CommandRun run =
        test::run_kinray("collide " + args + " -q --json '" + json.string() + "'", m_dir);
    EXPECT_EQ(run.status, 0) << run.err;
    return run.status == 0 ? nlohmann::json::parse(test::read_text(json)) : nlohmann::json{};
  }

  fs::path m_dir;
};

/// The contacts without their points (which are rounded doubles, compared separately).
nlohmann::json identities(const nlohmann::json& report) {
  nlohmann::json out = nlohmann::json::array();
  for (nlohmann::json c : report["contacts"]) {
    c.erase("point");
    out.push_back(c);
  }
  return out;
}

TEST_F(CollideCommand, SpikeFallsOntoATriangleAtTheExpectedTime) {
  // a static triangle at z = 0 and a spike whose tip falls from z = 1 to z = -0.5 in one second:
  // the tip touches the triangle at t = 2/3, and nothing else ever touches
  const fs::path scene = m_dir / "spike.json";
  std::ofstream(scene) << R"({"shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]},
    "objects": [
      {"kind": "mesh", "name": "floor", "vertices": [[0, 0, 0], [1, 0, 0], [0, 1, 0]], "triangles": [[0, 1, 2]]},
      {"kind": "mesh", "name": "spike", "triangles": [[0, 1, 2]],
       "keys": [{"time": 0, "vertices": [[0.2, 0.2, 1], [0.2, 0.2, 2], [0.3, 0.2, 2]]},
                {"time": 1, "vertices": [[0.2, 0.2, -0.5], [0.2, 0.2, 0.5], [0.3, 0.2, 0.5]]}]}]})";
  for (const char* structure : {"brute", "swept", "ksl"}) {
    SCOPED_TRACE(structure);
    const nlohmann::json report = collide("'" + scene.string() + "' --structure " + structure);
    ASSERT_EQ(report["contacts"].size(), 1u);
    const nlohmann::json& c = report["contacts"][0];
    EXPECT_EQ(c["type"], "vf");
    EXPECT_EQ(c["objects"], (nlohmann::json{1, 0}));
    EXPECT_EQ(c["vertices"], (nlohmann::json{0, 0, 1, 2}));
    EXPECT_LE(c["time"].get<double>(), 2.0 / 3.0);
    EXPECT_NEAR(c["time"].get<double>(), 2.0 / 3.0, 1e-12);
    EXPECT_NEAR(c["point"][2].get<double>(), 0.0, 1e-12);
  }
}

TEST_F(CollideCommand, KslSweptVolumesAndBruteForceFindTheSameContactsInTimeOrder) {
  for (const char* scene : {"cloth-fold:triangles=72,duration=1,keyrate=4 --self",
                            "crossing:triangles=100,duration=1,keyrate=4",
                            "crossing:triangles=60,duration=1,keyrate=4 --self"}) {
    SCOPED_TRACE(scene);
    const nlohmann::json ksl = collide(std::string(scene) + " --structure ksl --audit");
    const nlohmann::json ksl_checks =
        collide(std::string(scene) + " --structure ksl --audit --checks 7");
    const nlohmann::json swept = collide(std::string(scene) + " --structure swept");
    const nlohmann::json swept_checks = collide(std::string(scene) + " --structure swept --checks 5");
    const nlohmann::json brute = collide(std::string(scene) + " --structure brute");
    EXPECT_GT(brute["contacts"].size(), 10u) << "the scene has real contacts";
    EXPECT_EQ(identities(swept), identities(brute));
    EXPECT_EQ(identities(swept_checks), identities(brute)) << "checks on sub-intervals";
    EXPECT_EQ(identities(ksl), identities(brute));
    EXPECT_EQ(identities(ksl_checks), identities(brute));
    // the list's events do not depend on how often it is asked
    EXPECT_EQ(ksl["stats"]["ksl"]["events"], ksl_checks["stats"]["ksl"]["events"]);
    for (const nlohmann::json* report : {&swept, &ksl, &ksl_checks}) {
      double last = -1;
      for (const nlohmann::json& c : (*report)["contacts"]) {
        EXPECT_GE(c["time"].get<double>(), last);
        last = c["time"].get<double>();
      }
    }
    // the swept boxes and the list prune: fewer triangle pairs reach the primitive tests
    EXPECT_LT(swept["stats"]["triangle_pairs"].get<double>(),
              brute["stats"]["triangle_pairs"].get<double>());
    EXPECT_LT(ksl["stats"]["triangle_pairs"].get<double>(),
              brute["stats"]["triangle_pairs"].get<double>());
    EXPECT_GT(ksl["stats"]["ksl"]["events"]["overlap"].get<double>(), 0);
    EXPECT_TRUE(ksl["stats"]["ksl"]["quality"].contains("efficiency"));
  }
}

TEST_F(CollideCommand, BenchComparesKslWithSweptVolumesOnTheSameContacts) {
  const fs::path json = m_dir / "bench.json";
  const test::CommandRun run = test::run_kinray(
      "bench crossing:triangles=60,duration=0.5,keyrate=4 --structure ksl,swept --inbetweens 1,8 "
      "--triangles 40 --repetitions 1 -q --json '" + json.string() + "'", m_dir);
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(test::read_text(json));
  ASSERT_EQ(report["points"].size(), 6u);  // 2 structures x (2 interpolated-frame counts + 1)
  for (const nlohmann::json& p : report["points"]) {
    for (const char* key : {"structure", "interpolated_frames", "triangles", "ms_per_frame",
                            "contacts", "speedup_vs_swept"})
      EXPECT_TRUE(p.contains(key)) << key;
    EXPECT_GT(p["ms_per_frame"].get<double>(), 0);
  }
  EXPECT_EQ(report["points"][0]["contacts"], report["points"][1]["contacts"]);
  EXPECT_EQ(report["points"][0]["ksl_events"], report["points"][2]["ksl_events"])
      << "the list's events do not depend on the interpolated frames";
}

TEST_F(CollideCommand, SelfContactsExcludeAdjacentTriangles) {
  // the cloth at rest before the fold: neighbours share vertices and edges but are not contacts
  const nlohmann::json report =
      collide("cloth-fold:triangles=72,duration=1,keyrate=4 --self --time 0:0.25");
  EXPECT_EQ(report["contacts"].size(), 0u);
}

TEST_F(CollideCommand, SelfContactsExcludeTheTwoSidesOfASeam) {
  // Two triangles sharing an edge only by position (vertices 3 and 4 repeat 1 and 0 at every
  // key, as a texture seam of a skinned model is written), folding: neighbours, not a contact
  // along the seam at every instant; a third triangle falls through the fold and does touch it.
  const fs::path scene = m_dir / "seam.json";
  std::ofstream(scene) << R"({"shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"position": [0, 0, -5], "look_at": [0, 0, 0]}]},
    "objects": [
      {"kind": "mesh", "name": "seam", "triangles": [[0, 1, 2], [3, 4, 5], [6, 7, 8]],
       "keys": [{"time": 0, "vertices": [[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1, 0, 0], [0, 0, 0],
                                         [0.5, -1, 0], [0.4, -0.1, 1], [0.6, -0.1, 1], [0.5, 0.2, 1]]},
                {"time": 1, "vertices": [[0, 0, 0], [1, 0, 0], [0.5, 1, 0], [1, 0, 0], [0, 0, 0],
                                         [0.5, -0.8, 0.6], [0.4, -0.1, -1], [0.6, -0.1, -1],
                                         [0.5, 0.2, -1]]}]}]})";
  for (const char* structure : {"brute", "swept", "ksl"}) {
    SCOPED_TRACE(structure);
    const nlohmann::json report =
        collide("'" + scene.string() + "' --self --structure " + structure);
    ASSERT_FALSE(report["contacts"].empty());  // the falling triangle
    for (const nlohmann::json& c : report["contacts"]) {
      const std::vector<int> v = c["vertices"];
      // every contact is with the falling triangle (vertices 6 to 8)
      EXPECT_TRUE(std::ranges::any_of(v, [](int x) { return x >= 6; })) << c.dump();
    }
  }
}

TEST_F(CollideCommand, BadFlagsAreOneLineAndExitTwo) {
  for (const char* args :
       {"crossing --structure octree", "crossing --objects 0,7", "crossing --time 5:6",
        "crossing --checks 0"}) {
    const test::CommandRun run = test::run_kinray(std::string("collide ") + args, m_dir);
    EXPECT_EQ(run.status, 2) << args;
    EXPECT_EQ(run.err.rfind("kinray: error: ", 0), 0u) << run.err;
    EXPECT_TRUE(run.out.empty());
  }
}

}  // namespace
}  // namespace kinray
