#pragma once
// The numbered files of a render in its output folder (frame_00000.png, id_00000.png,
// depth_00000.tiff, ...), and the clean-up after a render: files of that pattern that the render
// did not write are an earlier, longer render's, and are removed so that the folder holds one
// render (a `frame_%05d.png` glob or an encoder would otherwise mix two).
#include <filesystem>
#include <string>
#include <vector>

namespace kinray {

/// "frame_00012.png" for ("frame", 12, ".png").
[[nodiscard]] std::string numbered_file(const std::string& prefix, size_t index,
                                        const char* extension);

/// The files a render writes for frame `index`: frame_N.png, and id_N.png and depth_N.tiff when
/// `aov` holds "id" and "depth".
[[nodiscard]] std::vector<std::string> frame_files(size_t index,
                                                   const std::vector<std::string>& aov);

/// Whether `name` is named like a kinray frame output: frame_N.png, id_N.png or depth_N.tiff, N
/// of 5 or more digits.
[[nodiscard]] bool is_frame_output(const std::string& name);

/// Removes from `folder` every file named like a kinray frame output -- frame_N.png, id_N.png or
/// depth_N.tiff, N of 5 or more digits -- that is not in `written` (file names). Other files are
/// left alone. Returns the names removed, sorted.
std::vector<std::string> remove_stale_frames(const std::filesystem::path& folder,
                                             const std::vector<std::string>& written);

}  // namespace kinray
