// A file cut short anywhere or with bytes overwritten is bad input like any other: every reader
// must answer it within seconds, with the scene or with one InputError, never a crash or a hang
// (assimp's PLY reader once spun without end on a header cut short, until the import's 300 s
// timeout). Samples of every format kinray reads are cut at many points and corrupted at others.
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "scenes/scene_loader.h"
#include "util/input_error.h"
#include "util/warning.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const fs::path kCorpus = fs::path(KINRAY_SOURCE_DIR) / "tests" / "fuzz" / "corpus";

/// One sample of each format: PLY ascii and binary, OBJ, glTF and GLB, DirectX X (text and
/// binary), BART's AFF and kinray's JSON.
const char* const kSamples[] = {
    "model_import/cube.ply",         "model_import/cube_binary.ply",
    "model_import/box.obj",          "model_import/translating_triangle.gltf",
    "model_import/skinned_quad.glb", "model_import/cube_text.x",
    "model_import/cube_binary.x",    "aff_scene/animated.aff",
    "scene_file/animated-mesh.json",
};

std::string read_bytes(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << file.rdbuf();
  return bytes.str();
}

/// The damaged versions of `bytes`: cut at the first bytes (inside a header) and at evenly spread
/// points, and with a byte overwritten at evenly spread points.
std::vector<std::pair<std::string, std::string>> damaged(const std::string& bytes) {
  std::vector<std::pair<std::string, std::string>> out;
  std::vector<size_t> cuts = {1, 3, 7, 12, 20, 31, 45, 64};
  for (size_t k = 1; k < 16; ++k) cuts.push_back(bytes.size() * k / 16);
  for (size_t cut : cuts)
    if (cut < bytes.size())
      out.emplace_back("cut at byte " + std::to_string(cut), bytes.substr(0, cut));
  std::mt19937 random(7);
  for (size_t k = 0; k < 12; ++k) {
    const size_t at = bytes.size() * k / 12;
    std::string copy = bytes;
    copy[at] = static_cast<char>(std::uniform_int_distribution<int>(0, 255)(random));
    out.emplace_back("byte " + std::to_string(at) + " overwritten", std::move(copy));
  }
  return out;
}

TEST(DamagedFiles, EveryReaderAnswersACutOrCorruptFileWithinSeconds) {
  const ScopedWarningSink quiet([](const std::string&) {});
  const fs::path folder =
      fs::temp_directory_path() / ("kinray_damaged_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  ModelOptions options;
  options.import_timeout = 20;  // a hang shows as a time over the limit below, not a 300 s wait
  size_t refused = 0, variants = 0;
  for (const char* sample : kSamples) {
    const fs::path source = kCorpus / sample;
    ASSERT_TRUE(fs::exists(source)) << source;
    for (const auto& [what, bytes] : damaged(read_bytes(source))) {
      SCOPED_TRACE(std::string(sample) + ", " + what);
      // the damaged copy keeps the sample's name, so that it is read as the same format
      const fs::path copy = folder / source.filename();
      std::ofstream(copy, std::ios::binary | std::ios::trunc) << bytes;
      const auto start = std::chrono::steady_clock::now();
      try {
        (void)load_scene(copy.string(), options);
      } catch (const InputError& error) {
        ++refused;
        EXPECT_NE(std::string(error.what()).find(copy.string()), std::string::npos)
            << "the error names the file: " << error.what();
        EXPECT_EQ(std::string(error.what()).find('\n'), std::string::npos) << error.what();
      }
      const double seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      EXPECT_LT(seconds, 10.0);
      ++variants;
    }
  }
  fs::remove_all(folder);
  // most damage is caught; some cuts leave a valid file (a whole line of an OBJ, say)
  EXPECT_GT(refused, variants / 2) << refused << " of " << variants << " refused";
}

}  // namespace
}  // namespace kinray
