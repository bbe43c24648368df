#include "tests/fuzz/fuzz_target.h"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "util/input_error.h"

namespace kinray::fuzz {

std::vector<Target>& targets() {
  static std::vector<Target> all;
  return all;
}

bool register_target(std::string name, Entry entry) {
  targets().push_back({std::move(name), entry});
  return true;
}

void run_target(Entry entry, std::span<const uint8_t> bytes) {
  try {
    entry(bytes);
  } catch (const InputError&) {
    // The refusal the project's rules ask for: one clear line naming the input.
  }
}

namespace {

/// Removes the scratch folder when the process ends normally.
struct ScratchFolder {
  std::string path;
  ScratchFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "kinray-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) {
      std::perror("kinray fuzz: cannot create a scratch folder");
      std::abort();
    }
    path = pattern;
  }
  ~ScratchFolder() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

}  // namespace

const std::string& scratch_folder() {
  static const ScratchFolder folder;
  return folder.path;
}

std::string write_scratch_file(std::string_view name, std::span<const uint8_t> bytes) {
  const std::string path = scratch_folder() + "/" + std::string(name);
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr || std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) {
    std::perror("kinray fuzz: cannot write a scratch file");
    std::abort();
  }
  std::fclose(file);
  return path;
}

}  // namespace kinray::fuzz
