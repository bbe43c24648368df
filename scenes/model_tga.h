#pragma once
// Truevision TGA, the texture format of many game models (MD5, MDL, SMD, X, COLLADA's duck),
// which OpenCV 4.6's imgcodecs cannot read: uncompressed and run-length encoded true-colour
// (24 or 32 bits) and grey (8 bits) images.
#include <cstdint>
#include <opencv2/core.hpp>
#include <span>

namespace kinray {

/// Decodes a TGA file held in `bytes` into an 8-bit BGR image with row 0 at the top; returns an
/// empty image for anything else (colour-mapped or 15/16-bit TGA, truncated data, not a TGA).
[[nodiscard]] cv::Mat decode_tga(std::span<const uint8_t> bytes);

}  // namespace kinray
