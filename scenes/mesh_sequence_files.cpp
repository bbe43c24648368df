// Which files a mesh sequence spec names, and their natural order (mesh_sequence.h).
#include <fnmatch.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "scenes/mesh_sequence.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

bool has_wildcard(std::string_view text) {
  return text.find_first_of("*?[") != std::string_view::npos;
}

std::string lower_extension(const fs::path& path) {
  std::string extension = path.extension().string();
  for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
  return extension;
}

bool is_mesh_extension(const std::string& extension) {
  return extension == ".ply" || extension == ".obj";
}

/// Every file of the glob `spec` (wildcards in the file name only).
std::vector<fs::path> glob_files(const std::string& spec) {
  const fs::path pattern(spec);
  const fs::path folder = pattern.has_parent_path() ? pattern.parent_path() : fs::path(".");
  if (has_wildcard(folder.string()))
    throw InputError(spec, "only the file name of a sequence pattern may hold wildcards");
  std::error_code error;
  if (!fs::is_directory(folder, error))
    throw InputError(spec, "no such folder '" + folder.string() + "'");
  const std::string name_pattern = pattern.filename().string();
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (fnmatch(name_pattern.c_str(), name.c_str(), FNM_PERIOD) != 0) continue;
    if (!entry.is_regular_file(error)) continue;
    if (!is_mesh_extension(lower_extension(entry.path())))
      throw InputError(spec, "matches '" + entry.path().string() +
                                 "', which is neither a .ply nor an .obj file");
    files.push_back(entry.path());
  }
  if (error) throw InputError(spec, "cannot list '" + folder.string() + "': " + error.message());
  if (files.empty()) throw InputError(spec, "matches no files (an empty sequence)");
  return files;
}

/// Every .ply or .obj file of the folder `spec`.
std::vector<fs::path> folder_files(const std::string& spec) {
  std::error_code error;
  std::vector<fs::path> files;
  for (const fs::directory_entry& entry : fs::directory_iterator(spec, error))
    if (entry.is_regular_file(error) && is_mesh_extension(lower_extension(entry.path())))
      files.push_back(entry.path());
  if (error) throw InputError(spec, "cannot list the folder: " + error.message());
  if (files.empty()) throw InputError(spec, "holds no .ply or .obj files (an empty sequence)");
  return files;
}

}  // namespace

bool is_mesh_sequence(const std::string& spec) {
  std::error_code error;
  if (fs::is_directory(spec, error)) return true;
  return has_wildcard(spec) && !fs::exists(spec, error);
}

bool natural_less(std::string_view a, std::string_view b) {
  size_t i = 0, j = 0;
  const auto digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  while (i < a.size() && j < b.size()) {
    if (digit(a[i]) && digit(b[j])) {
      size_t ei = i, ej = j;
      while (ei < a.size() && digit(a[ei])) ++ei;
      while (ej < b.size() && digit(b[ej])) ++ej;
      std::string_view x = a.substr(i, ei - i), y = b.substr(j, ej - j);
      x.remove_prefix(std::min(x.find_first_not_of('0'), x.size()));
      y.remove_prefix(std::min(y.find_first_not_of('0'), y.size()));
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = ei;
      j = ej;
      continue;
    }
    if (a[i] != b[j]) return a[i] < b[j];
    ++i;
    ++j;
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return a < b;
}

std::vector<std::string> mesh_sequence_files(const std::string& spec) {
  std::error_code error;
  const std::vector<fs::path> paths =
      fs::is_directory(spec, error) ? folder_files(spec) : glob_files(spec);
  const std::string first_extension = lower_extension(paths.front());
  for (const fs::path& path : paths)
    if (lower_extension(path) != first_extension)
      throw InputError(spec, "mixes .ply and .obj files ('" + paths.front().filename().string() +
                                 "', '" + path.filename().string() +
                                 "'); name one kind with a glob");
  std::vector<std::string> files;
  for (const fs::path& path : paths) files.push_back(path.string());
  std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) {
    return natural_less(fs::path(a).filename().string(), fs::path(b).filename().string());
  });
  return files;
}

}  // namespace kinray
