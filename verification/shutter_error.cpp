#include "verification/shutter_error.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>

#include "renderer/output/image_io.h"

namespace kinray {

void write_error_png(const Frame& a, const Frame& b, const std::string& path, double gain,
                     const std::vector<uint8_t>* aside) {
  cv::Mat image(a.height, a.width, CV_8UC3);
  for (int j = 0; j < a.height; ++j)
    for (int i = 0; i < a.width; ++i) {
      const size_t p = a.index(i, j);
      if (aside && (*aside)[p]) {
        image.at<cv::Vec3b>(j, i) = cv::Vec3b(0, 255, 255);  // yellow, as a sharp diff's tie
        continue;
      }
      const double e = (a.color[p] - b.color[p]).cwiseAbs().maxCoeff();
      // Grey up to half scale, then red: small errors stay visible, large ones stand out.
      const double v = std::clamp(e * gain, 0.0, 1.0);
      const auto grey = uint8_t(std::lround(255 * std::min(v, 0.5)));
      const auto red = uint8_t(std::lround(255 * v));
      image.at<cv::Vec3b>(j, i) = v > 0.5 ? cv::Vec3b(0, 0, red) : cv::Vec3b(grey, grey, grey);
    }
  write_image(path, image);
}

}  // namespace kinray
