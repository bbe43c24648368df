// The TGA texture decoder (scenes/model_tga.h): an image it returns has the header's size.
#include <cstdlib>

#include "scenes/model_tga.h"
#include "tests/fuzz/fuzz_target.h"

KINRAY_FUZZ_TARGET(tga) {
  const cv::Mat image = kinray::decode_tga(bytes);
  if (image.empty()) return;
  const int width = bytes[12] | (bytes[13] << 8), height = bytes[14] | (bytes[15] << 8);
  if (image.cols != width || image.rows != height || image.type() != CV_8UC3) std::abort();
}
