#pragma once
// The image formats kinray lets OpenCV decode, told apart by their first bytes. cv::imread and
// cv::imdecode choose a decoder by the content, not the file's name, and some of the decoders
// Debian's OpenCV links (gdcm for DICOM, OpenEXR, JPEG 2000) assert or abort on malformed input:
// a fuzzed "depth.tiff" holding a DICOM stream aborted the process inside gdcm. Textures and
// reference images are PNG, JPEG, BMP, TIFF, PNM or WebP in practice (TGA has its own decoder,
// scenes/model_tga.h), so every read checks the signature first and names what it found.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string_view>

namespace kinray {

enum class ImageSignature { png, jpeg, bmp, tiff, pnm, webp, other };

/// The format whose signature `head` (a file's first bytes; 12 are enough) begins with.
[[nodiscard]] ImageSignature image_signature(std::span<const uint8_t> head);

/// The signature of the file at `path`; `other` if it cannot be opened or is too short.
[[nodiscard]] ImageSignature image_signature_of_file(const std::filesystem::path& path);

/// Whether OpenCV may be handed an image of this signature.
[[nodiscard]] constexpr bool opencv_may_decode(ImageSignature s) {
  return s != ImageSignature::other;
}

/// "PNG", "JPEG", ... for messages; "an unsupported format" for `other`.
[[nodiscard]] std::string_view image_signature_name(ImageSignature s);

/// The formats OpenCV is allowed, for error messages.
inline constexpr std::string_view kDecodableImageFormats = "PNG, JPEG, BMP, TIFF, PNM or WebP";

}  // namespace kinray
