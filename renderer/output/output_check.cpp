#include "renderer/output/output_check.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// Creates and removes a probe file in `folder`: access(2) says yes to root on read-only
/// permissions and knows nothing of /proc, so only creating a file tells.
void probe_writable(const fs::path& folder, const std::string& path, const char* flag) {
  const fs::path probe = folder / (".kinray-probe." + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL, 0600);
  if (fd < 0) {
    const int error = errno;
    throw InputError(flag, "cannot write '" + path + "': '" + folder.string() +
                               "' does not take new files (" + std::strerror(error) + ")");
  }
  ::close(fd);
  ::unlink(probe.c_str());
}

/// The nearest folder at or above `path` that exists; throws when something on the way is not a
/// folder.
fs::path nearest_existing_folder(fs::path path, const std::string& shown, const char* flag) {
  std::error_code error;
  for (;;) {
    if (path.empty()) path = ".";
    if (fs::exists(path, error)) {
      if (!fs::is_directory(path, error))
        throw InputError(flag,
                         "cannot write '" + shown + "': '" + path.string() + "' is not a folder");
      return path;
    }
    if (path == path.parent_path() || path == ".") return ".";
    path = path.parent_path();
  }
}

void refuse_empty(const std::string& path, const char* flag) {
  if (path.empty()) throw InputError(flag, "the path is empty (an unset shell variable?)");
}

}  // namespace

void check_output_file(const std::string& path, const char* flag) {
  refuse_empty(path, flag);
  std::error_code error;
  const fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) throw InputError(flag, "'" + path + "' is a folder");
  if (fs::exists(status) && !fs::is_regular_file(status)) {
    // A device or a pipe is written in place, not replaced.
    if (::access(path.c_str(), W_OK) != 0)
      throw InputError(flag, "cannot write '" + path + "': " + std::strerror(errno));
    return;
  }
  probe_writable(nearest_existing_folder(fs::path(path).parent_path(), path, flag), path, flag);
}

void check_output_folder(const std::string& path, const char* flag) {
  refuse_empty(path, flag);
  std::error_code error;
  if (fs::exists(path, error) && !fs::is_directory(path, error))
    throw InputError(flag, "'" + path + "' exists and is not a folder");
  probe_writable(nearest_existing_folder(path, path, flag), path, flag);
}

void create_output_folder(const std::filesystem::path& folder, const char* flag) {
  if (folder.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error)
    throw InputError(flag,
                     "cannot create the folder '" + folder.string() + "': " + error.message());
}

}  // namespace kinray
