#pragma once
// The --json FILE of ccd-queries and collide: checked, and its folder made, before any work.
#include <filesystem>
#include <string>
#include <system_error>

#include "renderer/output/output_check.h"
#include "tools/cli_options.h"
#include "util/input_error.h"

namespace kinray {

/// Throws InputError naming --json when `path` is a folder or its folder cannot be created.
inline void prepare_json_output(const std::string& path) {
  if (path.empty()) return;
  std::error_code error;
  if (std::filesystem::is_directory(path, error))
    throw InputError("--json", "'" + path + "' is a folder");
  create_output_folder(std::filesystem::path(path).parent_path(), "--json");
}

}  // namespace kinray
