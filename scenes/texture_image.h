#pragma once
// Decoded 8-bit images into kinray's linear-RGB textures: the one conversion every texture source
// uses (JSON scene files, models' files and embedded textures, BART's PPM files), with one limit
// on their size.
#include <cstddef>
#include <cstdint>
#include <string>

#include "scenes/scene.h"

namespace cv {
class Mat;
}

namespace kinray {

/// 8192 x 8192: past this a texture costs more memory than a scene is worth.
inline constexpr size_t kMaxTexels = size_t(8192) * 8192;

/// The sRGB transfer curve (IEC 61966-2-1): encoded value in [0, 1] to linear intensity.
[[nodiscard]] float srgb_decode(double encoded);
/// sRGB-encoded 8-bit value to linear intensity in [0, 1] (the IEC 61966-2-1 curve): image files
/// hold sRGB, kinray shades in linear RGB.
[[nodiscard]] float srgb_to_linear(uint8_t value);

/// A decoded 3-channel 8-bit BGR image (OpenCV's order) as a texture named `path`. The caller has
/// checked that `image` is CV_8UC3 and has at most kMaxTexels texels.
[[nodiscard]] Texture texture_from_bgr(const cv::Mat& image, const std::string& path);

}  // namespace kinray
