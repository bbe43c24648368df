// Every input kept for the fuzz targets -- the seed corpus (tests/fuzz/corpus/NAME/) and the
// inputs that once made a harness crash, hang or throw (tests/fuzz/regressions/NAME/) -- replayed
// through the same entry point the libFuzzer harness calls. Each must be parsed or refused with
// an InputError; in the sanitizer build, without a sanitizer report.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "tests/fuzz/fuzz_target.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

const fs::path kFuzzDir = fs::path(KINRAY_SOURCE_DIR) / "tests" / "fuzz";

std::vector<uint8_t> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// The saved inputs of `target` under `kind` ("corpus" or "regressions"), sorted.
std::vector<fs::path> saved_inputs(const std::string& kind, const std::string& target) {
  std::vector<fs::path> files;
  const fs::path folder = kFuzzDir / kind / target;
  if (!fs::is_directory(folder)) return files;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.is_regular_file() && entry.path().filename() != "README.md")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  for (const fuzz::Target& target : fuzz::targets()) names.push_back(target.name);
  return names;
}

class FuzzReplay : public ::testing::TestWithParam<std::string> {};

// The generator runs after static initialisation, when every target has registered.
INSTANTIATE_TEST_SUITE_P(Targets, FuzzReplay, ::testing::ValuesIn(target_names()),
                         [](const auto& param) { return param.param; });

TEST_P(FuzzReplay, EverySavedInputIsParsedOrRefusedCleanly) {
  const auto found = std::find_if(fuzz::targets().begin(), fuzz::targets().end(),
                                  [](const fuzz::Target& t) { return t.name == GetParam(); });
  ASSERT_NE(found, fuzz::targets().end());
  const std::vector<fs::path> seeds = saved_inputs("corpus", GetParam());
  EXPECT_FALSE(seeds.empty()) << "a fuzz target needs seed inputs in tests/fuzz/corpus/"
                              << GetParam() << "/";
  std::vector<fs::path> inputs = seeds;
  for (const fs::path& path : saved_inputs("regressions", GetParam())) inputs.push_back(path);
  for (const fs::path& path : inputs) {
    const std::vector<uint8_t> bytes = read_bytes(path);
    EXPECT_NO_THROW(fuzz::run_target(found->entry, bytes))
        << path.lexically_relative(kFuzzDir).string();
  }
}

TEST(FuzzCorpus, EveryInputFolderBelongsToATarget) {
  const std::vector<std::string> names = target_names();
  const std::set<std::string> known(names.begin(), names.end());
  EXPECT_EQ(known.size(), names.size()) << "two fuzz targets share a name";
  for (const char* kind : {"corpus", "regressions"}) {
    if (!fs::is_directory(kFuzzDir / kind)) continue;
    for (const auto& entry : fs::directory_iterator(kFuzzDir / kind)) {
      if (!entry.is_directory()) continue;
      EXPECT_TRUE(known.count(entry.path().filename().string()))
          << kind << "/" << entry.path().filename().string() << " has no KINRAY_FUZZ_TARGET";
    }
  }
}

}  // namespace
}  // namespace kinray
