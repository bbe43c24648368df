#include "renderer/image_io.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "renderer/temporary_files.h"
#include "scenes/texture_image.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// thresholds[c] is the linear intensity at which the 8-bit code goes from c to c + 1, so that
/// encoding is a search over exact decision points instead of a pow per channel.
const std::array<float, 255>& srgb_thresholds() {
  static const std::array<float, 255> thresholds = [] {
    std::array<float, 255> t{};
    for (int c = 0; c < 255; ++c) t[size_t(c)] = srgb_decode((c + 0.5) / 255.0);
    return t;
  }();
  return thresholds;
}

void resize_if_needed(Frame& frame, int width, int height) {
  if (frame.width != width || frame.height != height ||
      frame.pixel_count() != size_t(width) * size_t(height))
    frame.resize(width, height);
}

cv::Mat read_image(const std::string& path, int flags) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) throw InputError(path, "no such file");
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

uint8_t linear_to_srgb8(float linear) {
  if (!(linear > 0.0f)) return 0;  // also NaN
  const auto& t = srgb_thresholds();
  return uint8_t(std::upper_bound(t.begin(), t.end(), linear) - t.begin());
}

cv::Mat color_image(const Frame& frame) {
  cv::Mat image(frame.height, frame.width, CV_8UC3);
  for (int j = 0; j < frame.height; ++j) {
    auto* row = image.ptr<cv::Vec3b>(j);
    for (int i = 0; i < frame.width; ++i) {
      const Color& c = frame.color[frame.index(i, j)];
      row[i] = cv::Vec3b(linear_to_srgb8(c.z()), linear_to_srgb8(c.y()), linear_to_srgb8(c.x()));
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
  cv::Mat image = read_image(path, cv::IMREAD_COLOR);
  if (image.type() != CV_8UC3) throw InputError(path, "not an 8-bit colour image");
  return image;
}

void read_id_png(const std::string& path, Frame& frame) {
  const cv::Mat image = read_image(path, cv::IMREAD_UNCHANGED);
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
  const cv::Mat image = read_image(path, cv::IMREAD_UNCHANGED);
  if (image.type() != CV_32FC1)
    throw InputError(path, "not a depth buffer (expected a 32-bit float TIFF)");
  resize_if_needed(frame, image.cols, image.rows);
  for (int j = 0; j < image.rows; ++j) {
    const auto* row = image.ptr<float>(j);
    for (int i = 0; i < image.cols; ++i) frame.depth[frame.index(i, j)] = row[i];
  }
}

}  // namespace kinray
