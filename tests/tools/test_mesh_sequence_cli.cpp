// Mesh sequences through the commands: a deforming PLY sequence rendered by the kinetic backend
// agrees with Embree (`diff`, 0 real mismatches), `info` names it a sequence, `collide` reads an
// OBJ sequence, and a file of another topology is one error line naming it (exit 2).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/job/render_job.h"
#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

/// A rippling sheet of (n x n) quads as a binary little-endian PLY with double coordinates.
void write_sheet(const std::string& path, int n, int frame, double lift = 0) {
  std::ofstream file(path, std::ios::binary);
  file << "ply\nformat binary_little_endian 1.0\nelement vertex " << (n + 1) * (n + 1)
       << "\nproperty double x\nproperty double y\nproperty double z\nelement face " << n * n
       << "\nproperty list uchar uint vertex_indices\nend_header\n";
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = 2.0 * i / n - 1, y = 2.0 * j / n - 1;
      const double xyz[3] = {x, y, lift + 0.3 * std::sin(3 * x + 0.4 * frame) * std::cos(2 * y)};
      file.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const unsigned char corners = 4;
      const uint32_t v[4] = {uint32_t(i * (n + 1) + j), uint32_t((i + 1) * (n + 1) + j),
                             uint32_t((i + 1) * (n + 1) + j + 1), uint32_t(i * (n + 1) + j + 1)};
      file.write(reinterpret_cast<const char*>(&corners), 1);
      file.write(reinterpret_cast<const char*>(v), sizeof v);
    }
}

class MeshSequenceCommands : public test::CommandTest {};

TEST_F(MeshSequenceCommands, RenderedSequenceAgreesWithEmbree) {
  std::filesystem::create_directories(path("sim"));
  for (int frame = 0; frame < 12; ++frame)
    write_sheet(path("sim/frame_" + std::to_string(frame) + ".ply"), 12, frame);
  const test::CommandRun run =
      kinray("diff '" + path("sim/frame_*.ply") + "' --size 64x48 --inbetweens 2 -q --json " +
             path("diff.json"));
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json diff = nlohmann::json::parse(test::read_text(path("diff.json")));
  EXPECT_EQ(diff["reference"], "embree");
  EXPECT_EQ(diff["frames"], 23);  // 11 key intervals, 2 frames each, and the last key
  EXPECT_EQ(diff["mismatch_real"], 0);

  const test::CommandRun info = kinray("info " + path("sim"));
  ASSERT_EQ(info.status, 0) << info.err;
  EXPECT_NE(info.out.find("mesh sequence with 12 frames (one file per key, 24 keys/s)"),
            std::string::npos)
      << info.out;
  EXPECT_NE(info.out.find("triangles   288"), std::string::npos) << info.out;
}

TEST_F(MeshSequenceCommands, CollideReadsAnObjSequence) {
  // two squares (objects a, b) in a plane each, b falling through a between frames 1 and 2
  std::filesystem::create_directories(path("obj"));
  for (int frame = 1; frame <= 3; ++frame) {
    std::ofstream file(path("obj/step" + std::to_string(frame) + ".obj"));
    const double z = 1.5 - frame;  // 0.5, -0.5, -1.5
    file << "o a\nv -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3 4\n"
         << "o b\nv -0.2 -0.2 " << z << "\nv 0.3 -0.2 " << z << "\nv 0.3 0.3 " << z
         << "\nv -0.2 0.3 " << z + 0.1 << "\nf -4 -3 -2 -1\n";
  }
  const test::CommandRun run =
      kinray("collide " + path("obj") + " --keyrate 10 -q --json " + path("c.json"));
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json contacts =
      nlohmann::json::parse(test::read_text(path("c.json")))["contacts"];
  ASSERT_FALSE(contacts.empty());
  // b's corners reach z = 0 between the first key (t = 0) and the second (t = 0.1)
  for (const nlohmann::json& c : contacts) {
    EXPECT_GE(c["time"].get<double>(), 0.0);
    EXPECT_LE(c["time"].get<double>(), 0.1 + 1e-9);
  }
}

TEST_F(MeshSequenceCommands, AFileOfAnotherTopologyIsOneErrorLine) {
  std::filesystem::create_directories(path("sim"));
  write_sheet(path("sim/f1.ply"), 4, 1);
  write_sheet(path("sim/f2.ply"), 5, 2);
  const test::CommandRun run = kinray("render " + path("sim") + " --out " + path("out"));
  EXPECT_EQ(run.status, 2);
  EXPECT_EQ(run.err, "kinray: error: " + path("sim/f2.ply") +
                         ": topology differs from the sequence's first file: mesh 0 has 36 "
                         "vertices here, 25 in the first file (f1.ply)\n");
  EXPECT_FALSE(std::filesystem::exists(path("out")));
}

TEST(MeshSequenceNames, OutputFolderIsNamedAfterTheSequence) {
  EXPECT_EQ(scene_stem("sim/frame_*.ply"), "frame_");
  const std::string folder = std::filesystem::temp_directory_path().string() + "/";
  EXPECT_EQ(scene_stem(folder), std::filesystem::path(folder).parent_path().filename().string());
}

}  // namespace
}  // namespace kinray
