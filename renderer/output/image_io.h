#pragma once
// Frame output through OpenCV: the shaded colour as 8-bit sRGB PNG, and lossless per-pixel
// buffers for comparing backends:
//  - ID buffer, 16-bit RGB PNG: R = object index + 1 (0 = background), G = the primitive index's
//    high 16 bits, B = its low 16 bits;
//  - depth buffer, 32-bit float single-channel TIFF (camera-space z, +inf for background).
// Every file is written under a temporary name in the same folder and renamed into place, so a
// crash mid-write never leaves a torn file, and readers round-trip the buffers bit for bit.
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>

#include "renderer/frame.h"

namespace kinray {

/// 8-bit sRGB code of a linear intensity (IEC 61966-2-1 curve, clamped to [0, 1], rounded to
/// nearest); NaN gives 0.
[[nodiscard]] uint8_t linear_to_srgb8(float linear);

/// frame.color as an 8-bit sRGB image in OpenCV's BGR channel order.
[[nodiscard]] cv::Mat color_image(const Frame& frame);
/// The ID buffer image (CV_16UC3, OpenCV BGR order: B = prim low, G = prim high, R = object + 1).
/// Throws std::runtime_error if an object index does not fit in 16 bits.
[[nodiscard]] cv::Mat id_image(const Frame& frame);
/// The depth buffer image (CV_32FC1).
[[nodiscard]] cv::Mat depth_image(const Frame& frame);

/// Writes `bytes` to `path` through a temporary file in the same folder and a rename (an existing
/// device or pipe, such as /dev/stdout, is written in place). Throws std::runtime_error naming the
/// path when the write fails: outputs are checked beforehand (output_check.h), so a failure here
/// is the machine's (disk full, I/O error).
void write_file_atomically(const std::string& path, std::string_view bytes);
/// Encodes `image` in the format of `path`'s extension (.png, .tiff, ...) and writes it atomically.
void write_image(const std::string& path, const cv::Mat& image);

void write_color_png(const std::string& path, const Frame& frame);
void write_id_png(const std::string& path, const Frame& frame);
void write_depth_tiff(const std::string& path, const Frame& frame);

/// Reads an 8-bit colour image (BGR). Throws InputError naming the file if it is missing or broken.
[[nodiscard]] cv::Mat read_color_png(const std::string& path);
/// Reads an ID buffer into frame.object and frame.prim (background pixels get kNoHit in both). A
/// frame of another size is resized first. Throws InputError naming the file if it is missing or
/// not an ID buffer.
void read_id_png(const std::string& path, Frame& frame);
/// Reads a depth buffer into frame.depth; a frame of another size is resized first. Throws
/// InputError naming the file if it is missing or not a depth buffer.
void read_depth_tiff(const std::string& path, Frame& frame);

}  // namespace kinray
