// The kinray program as a user runs it: bad input gives one line on stderr and a non-zero exit
// without touching earlier output; good input writes the expected files.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/videoio.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "renderer/job/render_job.h"
#include "renderer/output/image_io.h"
#include "scenes/scene_loader.h"
#include "tests/rejected_where.h"
#include "tests/tools/kinray_process.h"
#include "tools/cli/image_flags.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

constexpr const char* kTinyScene = "wavy-sphere:triangles=600";

using Invocation = test::CommandRun;
using test::read_text;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> result;
  std::istringstream stream(text);
  for (std::string line; std::getline(stream, line);) result.push_back(line);
  return result;
}

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_cli_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }

  /// Runs `kinray <args>` with stdin closed and stdout/stderr captured.
  [[nodiscard]] Invocation kinray(const std::string& args) const { return test::run_kinray(args, m_dir); }
  [[nodiscard]] std::string path(const std::string& name) const { return (m_dir / name).string(); }

  fs::path m_dir;
};

/// Every bad invocation: status 2, one line on stderr containing `names`, earlier output untouched.
void expect_rejected(const Invocation& run, const std::string& names, const fs::path& keep,
                     const std::string& kept_bytes) {
  EXPECT_EQ(run.status, 2) << run.err;
  const std::vector<std::string> err = lines(run.err);
  ASSERT_EQ(err.size(), 1u) << run.err;
  EXPECT_EQ(err[0].rfind("kinray: error: ", 0), 0u) << err[0];
  EXPECT_NE(err[0].find(names), std::string::npos) << "expected '" << names << "' in: " << err[0];
  EXPECT_EQ(read_text(keep), kept_bytes) << "an earlier output file was changed";
  EXPECT_EQ(std::distance(fs::directory_iterator(keep.parent_path()), fs::directory_iterator()), 1)
      << "nothing may be written into the output folder";
}

TEST_F(Cli, BadInputIsOneLineAndLeavesEarlierOutputAlone) {
  fs::create_directories(path("out"));
  const fs::path keep = path("out/frame_00000.png");
  const std::string kept_bytes = "an earlier render's frame\n";
  std::ofstream(keep, std::ios::binary) << kept_bytes;
  std::ofstream(path("broken.json")) << "{ \"objects\": [ { \"triangles\": [[0, 1, 2]], ";

  const std::string out = " --out '" + path("out") + "'";
  struct Case {
    std::string args, names;
  };
  const std::vector<Case> cases = {
      {std::string("render ") + kTinyScene + " --size 0x0", "--size"},
      {std::string("render ") + kTinyScene + " --size 10", "--size"},
      {std::string("render ") + kTinyScene + " --frames -3", "--frames"},
      {std::string("render ") + kTinyScene + " --frames 0", "--frames"},
      {std::string("render ") + kTinyScene + " --threads -1", "--threads"},
      {std::string("render ") + kTinyScene + " --fps nan", "--fps"},
      {std::string("render ") + kTinyScene + " --backend warp-drive", "warp-drive"},
      {std::string("render ") + kTinyScene + " --aov id,normals", "--aov"},
      {std::string("render ") + kTinyScene + " --time 2:1", "--time"},
      {std::string("render ") + kTinyScene + " --video '" + path("v.mkv") + "'", "--video"},
      {"render '" + path("broken.json") + "'", "broken.json"},
      {"render '" + path("missing.json") + "'", "missing.json"},
      {"render no-such-scene", "no-such-scene"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.args);
    expect_rejected(kinray(c.args + out), c.names, keep, kept_bytes);
  }
  EXPECT_FALSE(fs::exists(path("v.mkv")));
}

TEST_F(Cli, RenderWritesTheFramesAndBuffers) {
  const Invocation run = kinray(std::string("render ") + kTinyScene +
                                " --backend embree --size 32x24 --frames 3 --aov id,depth --out '" +
                                path("frames") + "' --stats '" + path("stats.json") + "' --quiet");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_EQ(run.err, "");
  EXPECT_EQ(run.out, "") << "--quiet prints nothing";
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(path("frames")))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names,
            (std::vector<std::string>{"depth_00000.tiff", "depth_00001.tiff", "depth_00002.tiff",
                                      "frame_00000.png", "frame_00001.png", "frame_00002.png",
                                      "id_00000.png", "id_00001.png", "id_00002.png"}));
  const cv::Mat colour = read_color_png(path("frames/frame_00001.png"));
  EXPECT_EQ(colour.cols, 32);
  EXPECT_EQ(colour.rows, 24);
  Frame frame;
  read_id_png(path("frames/id_00001.png"), frame);
  read_depth_tiff(path("frames/depth_00001.tiff"), frame);
  size_t hits = 0;
  for (size_t p = 0; p < frame.pixel_count(); ++p) {
    if (frame.object[p] == kNoHit) continue;
    ++hits;
    EXPECT_GT(frame.depth[p], 0.0f);
  }
  EXPECT_GT(hits, 20u) << "the sphere should cover part of the image";

  const nlohmann::json stats = nlohmann::json::parse(read_text(path("stats.json")));
  EXPECT_EQ(stats["frames"], 3);
  EXPECT_EQ(stats["backend"], "embree");
  EXPECT_EQ(stats["size"]["width"], 32);
  EXPECT_GT(stats["time_s"]["total"].get<double>(), 0.0);
  EXPECT_TRUE(stats["time_s"].contains("render"));
  EXPECT_EQ(stats["embree"]["frames"], 3);
}

TEST_F(Cli, VideoIsPlayable) {
  for (const char* name : {"clip.mp4", "clip.avi"}) {
    SCOPED_TRACE(name);
    const Invocation run =
        kinray(std::string("render ") + kTinyScene + " --size 64x48 --frames 5 --quiet --out '" +
               path("frames") + "' --video '" + path(name) + "'");
    ASSERT_EQ(run.status, 0) << run.err;
    cv::VideoCapture capture(path(name));
    ASSERT_TRUE(capture.isOpened());
    int frames = 0;
    cv::Mat image;
    while (capture.read(image)) {
      ++frames;
      EXPECT_EQ(image.cols, 64);
      EXPECT_EQ(image.rows, 48);
    }
    EXPECT_EQ(frames, 5);
  }
}

TEST_F(Cli, RenderSaysWhereTheFramesWent) {
  const Invocation run = kinray(std::string("render ") + kTinyScene +
                                " --size 16x16 --frames 2 --out '" + path("f") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find(path("f") + "/frame_00000.png"), std::string::npos) << run.out;
  EXPECT_TRUE(fs::exists(path("f/frame_00001.png")));
}

TEST_F(Cli, InfoPrintsTheTriangleCount) {
  const size_t triangles = load_scene(kTinyScene, {}).triangle_count();
  Invocation run = kinray(std::string("info ") + kTinyScene);
  ASSERT_EQ(run.status, 0) << run.err;
  EXPECT_NE(run.out.find("triangles   " + std::to_string(triangles) + "\n"), std::string::npos)
      << run.out;
  run = kinray(std::string("info ") + kTinyScene + " --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json info = nlohmann::json::parse(run.out);
  EXPECT_EQ(info["triangles"], triangles);
  EXPECT_EQ(info["objects"], 1);
}

TEST(RenderParams, ParseTheFlagsThatAreNotPlainNumbers) {
  EXPECT_EQ(parse_size("640x480"), std::make_pair(640, 480));
  EXPECT_EQ(parse_size("1x16384"), std::make_pair(1, 16384));
  for (const char* bad :
       {"0x0", "10", "x10", "10x", "-4x4", "4x-4", "4.5x4", "16385x1", "4x4x4", "", "axb", " 4x4"})
    EXPECT_THROW((void)parse_size(bad), InputError) << bad;
  EXPECT_EQ(parse_aov("id"), std::vector<std::string>{"id"});
  EXPECT_EQ(parse_aov("depth,id"), (std::vector<std::string>{"depth", "id"}));
  for (const char* bad : {"", "id,", "normal", "id,id", "ID"})
    EXPECT_THROW((void)parse_aov(bad), InputError) << bad;
}

TEST(RenderParams, DefaultOutputFolderIsNamedAfterTheScene) {
  EXPECT_EQ(scene_stem("wavy-sphere"), "wavy-sphere");
  EXPECT_EQ(scene_stem("cloth:triangles=2000,duration=1.5"), "cloth");
  EXPECT_EQ(scene_stem("scenes/examples/orbit.json"), "orbit");
  RenderParams params;
  params.scene = "orbit:triangles=100";
  EXPECT_EQ(output_folder(params), "out/orbit");
  params.out = "elsewhere";
  EXPECT_EQ(output_folder(params), "elsewhere");
}

// The library names the field at fault (OptionError); the command line turns it into the flag
// (CliFlags.ALibraryFieldIsNamedByItsFlag). The video path is still checked as a flag.
TEST(RenderParams, ValidationNamesTheField) {
  RenderParams params;
  params.scene = "wavy-sphere";
  EXPECT_NO_THROW(validate(params));
  RenderParams p = params;
  p.width = 0;
  EXPECT_EQ(test::rejected_where(p), "width");
  p = params;
  p.threads = -1;
  EXPECT_EQ(test::rejected_where(p), "threads");
  p = params;
  p.packet = 2;
  EXPECT_EQ(test::rejected_where(p), "packet");
  p = params;
  p.fps = -1;
  EXPECT_EQ(test::rejected_where(p), "fps");
  p = params;
  p.keyrate = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(test::rejected_where(p), "keyrate");
  p = params;
  p.video = "clip.gif";
  EXPECT_EQ(test::rejected_where(p), "--video");
}

TEST_F(Cli, EverySubcommandHasHelp) {
  for (const char* command : {"", "render ", "info "}) {
    const Invocation run = kinray(std::string(command) + "--help");
    EXPECT_EQ(run.status, 0) << command;
    EXPECT_NE(run.out.find("Usage"), std::string::npos) << command;
  }
  const Invocation run = kinray("frobnicate");
  EXPECT_EQ(run.status, 2);
  EXPECT_NE(run.err.find("frobnicate"), std::string::npos);
}

}  // namespace
}  // namespace kinray
