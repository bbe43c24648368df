#include "util/png_chunks.h"

#include <array>
#include <fstream>
#include <iterator>
#include <vector>

namespace kinray {
namespace {

/// The CRC-32 of PNG and zlib (polynomial 0xEDB88320, reflected), table-driven.
uint32_t crc32(std::span<const uint8_t> bytes) {
  static const std::array<uint32_t, 256> table = [] {
    std::array<uint32_t, 256> t{};
    for (uint32_t n = 0; n < 256; ++n) {
      uint32_t c = n;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[n] = c;
    }
    return t;
  }();
  uint32_t c = 0xFFFFFFFFu;
  for (uint8_t b : bytes) c = table[(c ^ b) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

uint32_t big_endian(std::span<const uint8_t> b) {
  return uint32_t(b[0]) << 24 | uint32_t(b[1]) << 16 | uint32_t(b[2]) << 8 | uint32_t(b[3]);
}

}  // namespace

std::optional<std::string> png_chunk_problem(std::span<const uint8_t> bytes) {
  size_t at = 8;  // past the signature
  while (true) {
    if (bytes.size() < at + 8)
      return "the PNG is cut short: it ends at byte " + std::to_string(bytes.size()) +
             " without its IEND chunk";
    const uint64_t length = big_endian(bytes.subspan(at, 4));
    const std::string type(bytes.begin() + std::ptrdiff_t(at + 4), bytes.begin() + std::ptrdiff_t(at + 8));
    if (length > uint64_t(bytes.size()) || at + 12 + length > bytes.size())
      return "the PNG is cut short: its chunk '" + type + "' at byte " + std::to_string(at) +
             " runs past the end";
    const uint32_t stored = big_endian(bytes.subspan(at + 8 + length, 4));
    if (crc32(bytes.subspan(at + 4, 4 + length)) != stored)
      return "the PNG is corrupt: its chunk '" + type + "' at byte " + std::to_string(at) +
             " fails its CRC";
    if (type == "IEND") return std::nullopt;
    at += 12 + length;
  }
}

std::optional<std::string> png_file_chunk_problem(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::nullopt;
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                   std::istreambuf_iterator<char>());
  return png_chunk_problem(bytes);
}

}  // namespace kinray
