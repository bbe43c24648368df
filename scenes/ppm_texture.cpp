#include "scenes/ppm_texture.h"

#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "scenes/texture_image.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// The header fields and pixel data of a PPM held in memory.
class PpmBytes {
 public:
  PpmBytes(std::string bytes, std::string where)
      : m_bytes(std::move(bytes)), m_where(std::move(where)) {}

  /// Next header integer, skipping white space and '#' comments.
  long long header_integer(const char* what) {
    skip_space_and_comments();
    long long value = 0;
    size_t digits = 0;
    while (m_at < m_bytes.size() && std::isdigit(static_cast<unsigned char>(m_bytes[m_at]))) {
      value = value * 10 + (m_bytes[m_at++] - '0');
      if (value > 1'000'000'000LL) fail(std::string(what) + " is too large");
      ++digits;
    }
    if (digits == 0) fail(std::string("expected ") + what + " in the header");
    return value;
  }
  /// The single white-space byte that ends a binary header.
  void end_of_header() {
    if (m_at >= m_bytes.size() || !std::isspace(static_cast<unsigned char>(m_bytes[m_at])))
      fail("expected one white-space byte after maxval");
    ++m_at;
  }
  unsigned byte() {
    if (m_at >= m_bytes.size()) fail("the pixel data is truncated");
    return static_cast<unsigned char>(m_bytes[m_at++]);
  }
  [[noreturn]] void fail(const std::string& problem) const { throw InputError(m_where, problem); }
  [[nodiscard]] const std::string& bytes() const { return m_bytes; }

 private:
  void skip_space_and_comments() {
    while (m_at < m_bytes.size()) {
      if (std::isspace(static_cast<unsigned char>(m_bytes[m_at])))
        ++m_at;
      else if (m_bytes[m_at] == '#')
        while (m_at < m_bytes.size() && m_bytes[m_at] != '\n') ++m_at;
      else
        break;
    }
  }
  std::string m_bytes, m_where;
  size_t m_at = 2;  // after the magic number
};

float to_linear(long long value, long long maxval) {
  if (maxval == 255) return srgb_to_linear(uint8_t(value));
  const double encoded = double(value) / double(maxval);
  return float(encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4));
}

}  // namespace

Texture read_ppm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), "cannot read the file");
  std::ostringstream content;
  content << in.rdbuf();
  PpmBytes ppm(content.str(), path.string());
  const std::string& bytes = ppm.bytes();
  if (bytes.size() < 2 || bytes[0] != 'P' || (bytes[1] != '6' && bytes[1] != '3'))
    ppm.fail("not a PPM image (expected the magic number P6 or P3)");
  const bool binary = bytes[1] == '6';
  const long long width = ppm.header_integer("the width"),
                  height = ppm.header_integer("the height");
  const long long maxval = ppm.header_integer("maxval");
  if (width < 1 || height < 1) ppm.fail("width and height must be at least 1");
  if (width * height > (long long)kMaxTexels) ppm.fail("more than 8192 x 8192 texels");
  if (maxval < 1 || maxval > 65535) ppm.fail("maxval must lie in 1..65535");
  if (binary) ppm.end_of_header();

  Texture texture;
  texture.path = path.string();
  texture.width = int(width);
  texture.height = int(height);
  texture.texels.resize(size_t(width * height));
  for (Color& texel : texture.texels) {
    for (int c = 0; c < 3; ++c) {
      long long value = 0;
      if (!binary)
        value = ppm.header_integer("a sample");
      else if (maxval < 256)
        value = ppm.byte();
      else {
        const long long high = ppm.byte();  // big-endian, most significant byte first
        value = (high << 8) | ppm.byte();
      }
      if (value > maxval) ppm.fail("a sample exceeds maxval");
      texel[c] = to_linear(value, maxval);
    }
  }
  return texture;
}

}  // namespace kinray
