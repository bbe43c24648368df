#include "renderer/output/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "renderer/output/temporary_files.h"
#include "scenes/texture_image.h"
#include "util/image_signature.h"
#include "util/png_chunks.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// The 8-bit sRGB code of a linear intensity, without a pow per channel: thresholds[c] is the
/// exact decision point at which the code goes from c to c + 1 (thresholds[255] is infinity), and
/// the codes of all floats in [0, 1) sharing their top 16 bits (an exponent and 7 mantissa bits)
/// differ by at most one, checked when the table is made. So a float's code is its bucket's first
/// code, plus one if it reaches the next threshold: a load and a compare, where a binary search
/// over the thresholds took eight mispredicted branches and 30% of a slow-motion render's time.
class SrgbEncoder {
 public:
  SrgbEncoder() {
    for (int c = 0; c < 255; ++c) m_thresholds[size_t(c)] = srgb_decode((c + 0.5) / 255.0);
    m_thresholds[255] = std::numeric_limits<float>::infinity();
    for (uint32_t b = 0; b < kBuckets; ++b) {
      const uint8_t first = search(std::bit_cast<float>(b << kShift));
      const uint8_t last = search(std::bit_cast<float>(((b + 1) << kShift) - 1));
      if (last - first > 1) throw std::logic_error("sRGB encoder: a bucket spans two thresholds");
      m_bucket_code[b] = first;
    }
  }

  [[nodiscard]] uint8_t encode(float linear) const {
    if (!(linear > 0.0f)) return 0;  // also NaN
    if (!(linear < 1.0f)) return 255;
    const uint8_t code = m_bucket_code[std::bit_cast<uint32_t>(linear) >> kShift];
    return uint8_t(code + uint8_t(linear >= m_thresholds[code]));
  }

  /// The code by binary search over the thresholds: the definition the buckets are made from.
  [[nodiscard]] uint8_t search(float linear) const {
    return uint8_t(std::upper_bound(m_thresholds.begin(), m_thresholds.end() - 1, linear) -
                   m_thresholds.begin());
  }

 private:
  static constexpr int kShift = 16;
  static constexpr uint32_t kBuckets = std::bit_cast<uint32_t>(1.0f) >> kShift;
  std::array<float, 256> m_thresholds{};
  std::array<uint8_t, kBuckets> m_bucket_code{};
};

const SrgbEncoder& srgb_encoder() {
  static const SrgbEncoder encoder;
  return encoder;
}

void resize_if_needed(Frame& frame, int width, int height) {
  if (frame.width != width || frame.height != height ||
      frame.pixel_count() != size_t(width) * size_t(height))
    frame.resize(width, height);
}

/// `path` decoded, once its first bytes show it is a `format` file: cv::imread would otherwise hand
/// a misnamed file to whichever decoder claims it (util/image_signature.h says why that matters).
cv::Mat read_image(const std::string& path, int flags, ImageSignature format) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw InputError(path, "no such file");
  const ImageSignature found = image_signature_of_file(path);
  if (found != format)
    throw InputError(path, "not a " + std::string(image_signature_name(format)) + " file (it is " +
                               (found == ImageSignature::other ? "" : "a ") +
                               std::string(image_signature_name(found)) + ")");
  if (format == ImageSignature::png)
    if (const std::optional<std::string> problem = png_file_chunk_problem(path))
      throw InputError(path, *problem);
  cv::Mat image;
  try {
    image = cv::imread(path, flags);
  } catch (const cv::Exception& e) {
    throw InputError(path, "cannot decode the image (" + std::string(e.err) + ")");
  }
  if (image.empty()) throw InputError(path, "cannot decode the image");
  return image;
}

}  // namespace

uint8_t linear_to_srgb8(float linear) { return srgb_encoder().encode(linear); }

cv::Mat color_image(const Frame& frame) {
  cv::Mat image(frame.height, frame.width, CV_8UC3);
  const SrgbEncoder& srgb = srgb_encoder();
  for (int j = 0; j < frame.height; ++j) {
    auto* row = image.ptr<cv::Vec3b>(j);
    for (int i = 0; i < frame.width; ++i) {
      const Color& c = frame.color[frame.index(i, j)];
      row[i] = cv::Vec3b(srgb.encode(c.z()), srgb.encode(c.y()), srgb.encode(c.x()));
    }
  }
  return image;
}

cv::Mat id_image(const Frame& frame) {
  cv::Mat image(frame.height, frame.width, CV_16UC3);
  for (int j = 0; j < frame.height; ++j) {
    auto* row = image.ptr<cv::Vec3w>(j);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      const uint32_t object = frame.object[p];
      if (object == kNoHit) {
        row[i] = cv::Vec3w(0, 0, 0);
        continue;
      }
      if (object >= 0xFFFFu)
        throw std::runtime_error("the ID buffer holds at most 65534 objects, pixel (" +
                                 std::to_string(i) + ", " + std::to_string(j) + ") shows object " +
                                 std::to_string(object));
      const uint32_t prim = frame.prim[p];
      row[i] = cv::Vec3w(uint16_t(prim & 0xFFFFu), uint16_t(prim >> 16), uint16_t(object + 1));
    }
  }
  return image;
}

cv::Mat depth_image(const Frame& frame) {
  cv::Mat image(frame.height, frame.width, CV_32FC1);
  for (int j = 0; j < frame.height; ++j) {
    auto* row = image.ptr<float>(j);
    for (int i = 0; i < frame.width; ++i) row[i] = frame.depth[frame.index(i, j)];
  }
  return image;
}

namespace {

/// Writes `bytes` into an open file and closes it; the errno of the first failure, or 0.
int write_and_close(std::FILE* file, std::string_view bytes) {
  int error_number = 0;
  if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) error_number = errno;
  if (std::fflush(file) != 0 && error_number == 0) error_number = errno;
  if (std::fclose(file) != 0 && error_number == 0) error_number = errno;
  return error_number;
}

/// A write that failed after the output was checked (disk full, I/O error): the machine's failure,
/// not bad input, so std::runtime_error (exit status 1).
[[noreturn]] void write_failed(const std::string& path, const std::string& problem) {
  throw std::runtime_error(path + ": cannot write: " + problem);
}

}  // namespace

void write_file_atomically(const std::string& path, std::string_view bytes) {
  const std::filesystem::path target(path);
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(target, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_directory(status)) {
    // A device or a pipe (/dev/stdout) cannot be replaced by a rename: it is written in place.
    std::FILE* file = std::fopen(path.c_str(), "wb");
    if (!file) write_failed(path, std::strerror(errno));
    if (const int error_number = write_and_close(file, bytes))
      write_failed(path, std::strerror(error_number));
    return;
  }
  // Appended piece by piece: GCC 12 warns (-Wrestrict, a false positive) on "." + std::string.
  std::string name(1, '.');
  name.append(target.filename().string()).append(".tmp").append(std::to_string(::getpid()));
  const TemporaryFile temporary((target.parent_path() / name).string());
  std::FILE* file = std::fopen(temporary.path().c_str(), "wb");
  if (!file) write_failed(path, std::strerror(errno));
  if (const int error_number = write_and_close(file, bytes)) {
    std::filesystem::remove(temporary.path(), error);
    write_failed(path, std::strerror(error_number));
  }
  std::filesystem::rename(temporary.path(), target, error);
  if (error) {
    std::error_code ignored;
    std::filesystem::remove(temporary.path(), ignored);
    write_failed(path, error.message());
  }
}

void write_image(const std::string& path, const cv::Mat& image) {
  std::vector<uchar> encoded;
  const std::string extension = std::filesystem::path(path).extension().string();
  bool ok = false;
  try {
    ok = cv::imencode(extension, image, encoded);
  } catch (const cv::Exception& e) {
    throw InputError(path, "cannot encode the image (" + std::string(e.err) + ")");
  }
  if (!ok) throw InputError(path, "cannot encode the image as " + extension);
  write_file_atomically(
      path, std::string_view(reinterpret_cast<const char*>(encoded.data()), encoded.size()));
}

void write_color_png(const std::string& path, const Frame& frame) {
  write_image(path, color_image(frame));
}
void write_id_png(const std::string& path, const Frame& frame) {
  write_image(path, id_image(frame));
}
void write_depth_tiff(const std::string& path, const Frame& frame) {
  write_image(path, depth_image(frame));
}

cv::Mat read_color_png(const std::string& path) {
  cv::Mat image = read_image(path, cv::IMREAD_COLOR, ImageSignature::png);
  if (image.type() != CV_8UC3) throw InputError(path, "not an 8-bit colour image");
  return image;
}

void read_id_png(const std::string& path, Frame& frame) {
  const cv::Mat image = read_image(path, cv::IMREAD_UNCHANGED, ImageSignature::png);
  if (image.type() != CV_16UC3)
    throw InputError(path, "not an ID buffer (expected a 16-bit RGB PNG)");
  resize_if_needed(frame, image.cols, image.rows);
  for (int j = 0; j < image.rows; ++j) {
    const auto* row = image.ptr<cv::Vec3w>(j);
    for (int i = 0; i < image.cols; ++i) {
      const size_t p = frame.index(i, j);
      const cv::Vec3w& v = row[i];
      if (v[2] == 0) {
        frame.object[p] = kNoHit;
        frame.prim[p] = kNoHit;
      } else {
        frame.object[p] = uint32_t(v[2]) - 1;
        frame.prim[p] = (uint32_t(v[1]) << 16) | uint32_t(v[0]);
      }
    }
  }
}

void read_depth_tiff(const std::string& path, Frame& frame) {
  const cv::Mat image = read_image(path, cv::IMREAD_UNCHANGED, ImageSignature::tiff);
  if (image.type() != CV_32FC1)
    throw InputError(path, "not a depth buffer (expected a 32-bit float TIFF)");
  resize_if_needed(frame, image.cols, image.rows);
  for (int j = 0; j < image.rows; ++j) {
    const auto* row = image.ptr<float>(j);
    for (int i = 0; i < image.cols; ++i) frame.depth[frame.index(i, j)] = row[i];
  }
}

}  // namespace kinray
