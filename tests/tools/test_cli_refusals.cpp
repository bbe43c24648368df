// Inputs a user can type that were once accepted, misreported or left to hang: each is refused
// before any work with one line naming its file or flag and exit status 2, and output that was
// already there is left as it was.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tests/tools/kinray_process.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTiny = "wavy-sphere:triangles=600";

/// A small valid scene file; `extra` goes into its top-level object.
std::string scene_json(const std::string& extra = "", const std::string& camera_up = "") {
  return R"({"shot": {"begin": 0, "end": 1},
    "camera": {"keys": [{"position": [0, 0, 5], "look_at": [0, 0, 0])" +
         camera_up + R"(}]},
    "objects": [{"kind": "sphere", "radius": 1, "triangles": 200}])" +
         extra + "}";
}

void write_text(const std::string& path, const std::string& text) {
  fs::create_directories(fs::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

class CliRefusals : public test::CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    // the output of an earlier render, which no refused run may touch
    write_text(path("out/frame_00000.png"), "earlier frame");
    write_text(path("out/stats.json"), "earlier stats");
  }
  /// Runs `kinray ARGS`; expects exit 2, one line starting "kinray: error: <where>: " and
  /// containing `problem`, and the earlier output unchanged.
  void refused(const std::string& args, const std::string& where, const std::string& problem) {
    SCOPED_TRACE(args);
    const auto start = std::chrono::steady_clock::now();
    const test::CommandRun run = kinray(args);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10);
    EXPECT_EQ(run.status, 2) << run.err;
    EXPECT_EQ(run.err.rfind("kinray: error: " + where + ": ", 0), 0u) << run.err;
    EXPECT_NE(run.err.find(problem), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(test::read_text(path("out/frame_00000.png")), "earlier frame");
    EXPECT_EQ(test::read_text(path("out/stats.json")), "earlier stats");
  }
  [[nodiscard]] std::string render(const std::string& scene = kTiny) const {
    return "render '" + scene + "' -q --out '" + path("out") + "' ";
  }
};

TEST_F(CliRefusals, OutputsOfOneRunMustBeDistinctFiles) {
  refused(render() + "--stats '" + path("out/frame_00001.png") + "'", "--stats",
          "named like one of the frames");
  refused(render() + "--stats '" + path("out/../out/id_00000.png") + "'", "--stats",
          "named like one of the frames");
  refused(render() + "--video '" + path("v.avi") + "' --stats '" + path("./v.avi") + "'", "--stats",
          "also the --video file");
  EXPECT_FALSE(fs::exists(path("v.avi")));
}

TEST_F(CliRefusals, AVideoNeedsFramesOfTwoByTwoPixels) {
  refused("render " + std::string(kTiny) + " --size 1x1 --frames 2 -q --out '" + path("out") +
              "' --video '" + path("one.avi") + "'",
          "--video", "at least 2x2 pixels");
  EXPECT_FALSE(fs::exists(path("one.avi")));
  // `kinray video` on 1x1 frames, and into a folder it cannot write, says so before encoding
  const test::CommandRun frames = kinray("render " + std::string(kTiny) +
                                         " --size 1x1 --frames 2 -q --out '" + path("tiny") + "'");
  ASSERT_EQ(frames.status, 0) << frames.err;
  refused("video '" + path("tiny") + "' --out '" + path("tiny.avi") + "'",
          path("tiny/frame_00000.png"), "at least 2x2 pixels");
  write_text(path("file"), "a file where a folder must be");
  refused("video '" + path("tiny") + "' --out '" + path("file/v.avi") + "'", "--out", "");
}

TEST_F(CliRefusals, NonFiniteAndHugeValuesAreRefused) {
  const std::string ply = path("nan.ply");
  write_text(ply,
             "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
             "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
             "end_header\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n");
  refused("info '" + ply + "'", ply + ":11", "coordinate z is NaN or infinite");
  const std::string inf = path("inf.ply");
  write_text(inf, test::read_text(ply).replace(test::read_text(ply).find("nan"), 3, "inf"));
  refused(render(inf), inf + ":11", "coordinate z is NaN or infinite");
  const std::string obj = path("nan.obj");
  write_text(obj, "v 0 0 0\nv 1 0 nan\nv 0 1 0\nf 1 2 3\n");
  refused("info '" + obj + "'", obj + ":2", "coordinate z is NaN or infinite");
  write_text(obj, "v 0 0 0\nv 1 0 0\nv 0 1e300 0\nf 1 2 3\n");
  refused("info '" + obj + "'", obj + ":3", "beyond +-1e15");
  refused(render() + "--light point:1e300,2,3", "--light", "beyond +-1e15");
  refused(render() + "--light dir:0,nan,1", "--light", "");
}

TEST_F(CliRefusals, ScenesThatOtherReadersRefuse) {
  const std::string twice = path("twice.json");
  write_text(twice, scene_json(R"(, "shot": {"begin": 0, "end": 2})"));
  refused(render(twice), twice + ": /shot", "given twice");
  const std::string nested = path("nested.json");
  write_text(nested, R"({"shot": {"begin": 0, "end": 1, "end": 2}, "objects": []})");
  refused(render(nested), nested + ": /shot/end", "given twice");
  const std::string up = path("up.json");
  write_text(up, scene_json("", R"(, "up": [0, 0, 2])"));
  refused(render(up), up + ": /camera/keys/0/up", "parallel to the viewing direction");
}

TEST_F(CliRefusals, NumbersOutOfRangeAreSaidSo) {
  refused(render() + "--frames 99999999999", "--frames", "'99999999999' is out of range");
  const std::string huge = "1" + std::string(300, '0');
  const test::CommandRun run = kinray(render() + "--frames " + huge);
  EXPECT_EQ(run.status, 2);
  EXPECT_LT(run.err.size(), 120u) << "a 300-digit number is not echoed whole: " << run.err;
}

TEST_F(CliRefusals, AMeshSequenceKeyedAbsurdlyFastIsRefusedAtOnce) {
  for (int frame = 0; frame < 3; ++frame)
    write_text(path("seq/f" + std::to_string(frame) + ".ply"),
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nelement face 1\nproperty list uchar int vertex_indices\n"
               "end_header\n0 0 " +
                   std::to_string(frame) + "\n1 0 0\n0 1 0\n3 0 1 2\n");
  for (const char* rate : {"1e300", "1e200", "2e6"})
    refused(render(path("seq/f*.ply")) + "--keyrate " + rate, "--keyrate", "[0, 1e6]");
}

TEST_F(CliRefusals, FlagsThatDoNotApplyAreRefused) {
  refused(render() + "--backend embree --shadow-tree boxtree", "--shadow-tree",
          "applies to the kinetic backend only");
  refused("collide crossing:triangles=60 --structure swept --audit -q", "--audit",
          "applies to --structure ksl only");
  refused("diff " + std::string(kTiny) + " --size 16x16 --frames 1 -q --reference-samples 64",
          "--reference-samples", "applies to --shutter");
  refused("diff " + std::string(kTiny) +
              " --size 16x16 --frames 1 -q --shutter 0.5 --reference-samples 0",
          "--reference-samples", "must lie in 1..");
}

TEST_F(CliRefusals, FilesAreNamedForTheirOwnProblems) {
  refused("ccd-queries '" + path("missing.csv") + "'", path("missing.csv"), "");
  const std::string queries = path("vertex-face/q.csv");
  std::string rows;
  for (int row = 0; row < 8; ++row)
    rows += "0,1,0,1," + std::to_string(row) + ",1," + (row == 5 ? "1" : "0") + "\n";
  write_text(queries, rows);
  refused("ccd-queries '" + queries + "'", queries + ":6", "disagrees with the query's first row");
  const std::string gltf = path("cut.gltf");
  write_text(gltf, R"({"asset": {"version": "2.0"}, "meshes": [{"primitives": [)");
  refused("info '" + gltf + "'", gltf, "truncated or corrupt");
  // a frame cut short and one with a changed byte: kinray's line alone, not libpng's before it
  ASSERT_EQ(kinray("render " + std::string(kTiny) + " --backend embree --size 16x16 --frames 2 -q "
                   "--out '" + path("frames") + "'")
                .status,
            0);
  const std::string frame = path("frames/frame_00001.png");
  const std::string bytes = test::read_text(frame);
  write_text(frame, bytes.substr(0, bytes.size() / 2));
  refused("video '" + path("frames") + "' --out '" + path("v.avi") + "'", frame, "cut short");
  std::string changed = bytes;
  changed[bytes.size() / 2] = char(changed[bytes.size() / 2] ^ 0x10);
  write_text(frame, changed);
  refused("video '" + path("frames") + "' --out '" + path("v.avi") + "'", frame, "fails its CRC");
  const std::string ply = path("cut.ply");
  write_text(ply, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nprop");
  refused("info '" + ply + "'", ply, "without an 'end_header' line");
}

TEST_F(CliRefusals, WhatTheRendererCannotDoYetIsRefusedNotApproximated) {
  const std::string aff = path("lit.aff");
  write_text(aff,
             "v\nfrom 0 0 10\nat 0 0 0\nup 0 1 0\nangle 40\nhither 0.1\nresolution 32 24\n"
             "la spot\n");
  refused(render(aff), aff + ":8", "animated lights (la) are not supported");
}

}  // namespace
}  // namespace kinray
