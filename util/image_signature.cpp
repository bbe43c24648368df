#include "util/image_signature.h"

#include <algorithm>
#include <array>
#include <fstream>

namespace kinray {
namespace {

bool starts_with(std::span<const uint8_t> head, std::string_view magic) {
  return head.size() >= magic.size() &&
         std::equal(magic.begin(), magic.end(), head.begin(),
                    [](char m, uint8_t b) { return uint8_t(m) == b; });
}

}  // namespace

ImageSignature image_signature(std::span<const uint8_t> head) {
  using namespace std::string_view_literals;
  if (starts_with(head, "\x89PNG\r\n\x1a\n"sv)) return ImageSignature::png;
  if (starts_with(head, "\xff\xd8\xff"sv)) return ImageSignature::jpeg;
  if (starts_with(head, "BM"sv)) return ImageSignature::bmp;
  // Little- and big-endian classic TIFF; BigTIFF (43) is left out, as nothing kinray reads is one.
  if (starts_with(head, "II*\0"sv) || starts_with(head, "MM\0*"sv)) return ImageSignature::tiff;
  // Netpbm: P1-P6 followed by white space (P7, PAM, is not one OpenCV 4.6 reads by that name).
  if (head.size() >= 3 && head[0] == 'P' && head[1] >= '1' && head[1] <= '6' &&
      (head[2] == ' ' || head[2] == '\t' || head[2] == '\n' || head[2] == '\r' || head[2] == '#'))
    return ImageSignature::pnm;
  if (starts_with(head, "RIFF"sv) && head.size() >= 12 &&
      starts_with(head.subspan(8), "WEBP"sv))
    return ImageSignature::webp;
  return ImageSignature::other;
}

ImageSignature image_signature_of_file(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::array<char, 12> head{};
  file.read(head.data(), head.size());
  const auto read = size_t(file.gcount());
  std::array<uint8_t, 12> bytes{};
  std::copy_n(head.begin(), read, bytes.begin());
  return image_signature(std::span<const uint8_t>(bytes.data(), read));
}

std::string_view image_signature_name(ImageSignature s) {
  switch (s) {
    case ImageSignature::png: return "PNG";
    case ImageSignature::jpeg: return "JPEG";
    case ImageSignature::bmp: return "BMP";
    case ImageSignature::tiff: return "TIFF";
    case ImageSignature::pnm: return "PNM";
    case ImageSignature::webp: return "WebP";
    case ImageSignature::other: break;
  }
  return "an unsupported format";
}

}  // namespace kinray
