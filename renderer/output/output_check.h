#pragma once
// Checks, before anything is rendered or written, that an output a flag names can be written: a
// command calls these for every output path it was given, so bad paths are refused (exit 2) with
// earlier output intact, instead of failing after the work is done. A check may create and remove
// a probe file in an existing folder; it creates no folder (create_output_folder does, once
// everything is valid and files are about to be written).
#include <filesystem>
#include <string>

namespace kinray {

/// Refuses (InputError naming `flag`) a file output that cannot be written: an empty path, a
/// folder, a path under something that is not a folder, or a place where no file can be created
/// (a read-only file system, missing permission, /proc). Missing parent folders are fine when the
/// nearest existing one is writable. Existing devices and pipes (/dev/stdout) are accepted.
void check_output_file(const std::string& path, const char* flag);

/// The same for an output folder: an empty path, an existing file, or a place where the folder
/// cannot be created or written into is refused.
void check_output_folder(const std::string& path, const char* flag);

/// Creates `folder` (and its parents) for the output named by `flag`; an empty path is the
/// working folder. Throws InputError naming the flag when it cannot.
void create_output_folder(const std::filesystem::path& folder, const char* flag);

}  // namespace kinray
