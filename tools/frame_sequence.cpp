#include "tools/frame_sequence.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <system_error>
#include <unordered_set>

namespace kinray {

bool is_frame_output(const std::string& name) {
  for (const auto& [prefix, extension] : {std::pair<std::string, std::string>{"frame_", ".png"},
                                          {"id_", ".png"},
                                          {"depth_", ".tiff"}}) {
    if (name.size() < prefix.size() + 5 + extension.size() || name.rfind(prefix, 0) != 0 ||
        name.compare(name.size() - extension.size(), extension.size(), extension) != 0)
      continue;
    const auto digits = std::string_view(name).substr(
        prefix.size(), name.size() - prefix.size() - extension.size());
    if (std::all_of(digits.begin(), digits.end(),
                    [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      return true;
  }
  return false;
}

std::string numbered_file(const std::string& prefix, size_t index, const char* extension) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%05zu%s", prefix.c_str(), index, extension);
  return name;
}

std::vector<std::string> frame_files(size_t index, const std::vector<std::string>& aov) {
  std::vector<std::string> names = {numbered_file("frame", index, ".png")};
  const auto has = [&](const char* name) {
    return std::find(aov.begin(), aov.end(), name) != aov.end();
  };
  if (has("id")) names.push_back(numbered_file("id", index, ".png"));
  if (has("depth")) names.push_back(numbered_file("depth", index, ".tiff"));
  return names;
}

std::vector<std::string> remove_stale_frames(const std::filesystem::path& folder,
                                             const std::vector<std::string>& written) {
  const std::unordered_set<std::string> keep(written.begin(), written.end());
  std::vector<std::string> removed;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file(error) || keep.count(name) || !is_frame_output(name)) continue;
    if (std::filesystem::remove(entry.path(), error)) removed.push_back(name);
  }
  std::sort(removed.begin(), removed.end());
  return removed;
}

}  // namespace kinray
