#pragma once
// PPM images (Netpbm P6 binary and P3 ASCII, maxval up to 65535), the texture format of BART's
// scenes, read into a linear-RGB kinray::Texture (the texels are taken as sRGB-encoded, as every
// 8-bit image file kinray reads).
#include <filesystem>

#include "scenes/scene.h"

namespace kinray {

/// Reads `path`. Throws InputError naming the file and the problem (not a PPM, truncated, bad
/// header, too large).
[[nodiscard]] Texture read_ppm(const std::filesystem::path& path);

}  // namespace kinray
