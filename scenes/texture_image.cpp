#include "scenes/texture_image.h"

#include <array>
#include <cmath>
#include <opencv2/core.hpp>

#include "util/check.h"

namespace kinray {

float srgb_decode(double encoded) {
  return float(encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4));
}

float srgb_to_linear(uint8_t value) {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[size_t(i)] = srgb_decode(i / 255.0);
    return t;
  }();
  return table[value];
}

Texture texture_from_bgr(const cv::Mat& image, const std::string& path) {
  KINRAY_CHECK(image.type() == CV_8UC3 && size_t(image.cols) * size_t(image.rows) <= kMaxTexels);
  Texture texture;
  texture.path = path;
  texture.width = image.cols;
  texture.height = image.rows;
  texture.texels.resize(size_t(image.cols) * size_t(image.rows));
  for (int y = 0; y < image.rows; ++y) {
    const cv::Vec3b* row = image.ptr<cv::Vec3b>(y);
    for (int x = 0; x < image.cols; ++x)
      texture.texels[size_t(y) * size_t(image.cols) + size_t(x)] =
          Color(srgb_to_linear(row[x][2]), srgb_to_linear(row[x][1]), srgb_to_linear(row[x][0]));
  }
  return texture;
}

}  // namespace kinray
