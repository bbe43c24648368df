// PNG chunks checked before decoding: a whole PNG passes, one cut anywhere or with a byte changed
// anywhere after its signature is named for what it is.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "util/png_chunks.h"

namespace kinray {
namespace {

std::vector<uint8_t> small_png() {
  cv::Mat image(7, 5, CV_8UC3);
  for (int j = 0; j < image.rows; ++j)
    for (int i = 0; i < image.cols; ++i) image.at<cv::Vec3b>(j, i) = cv::Vec3b(uchar(30 * i), uchar(20 * j), 90);
  std::vector<uint8_t> bytes;
  EXPECT_TRUE(cv::imencode(".png", image, bytes));
  return bytes;
}

TEST(PngChunks, AWholePngPassesAndEveryCutOrChangedByteIsFound) {
  const std::vector<uint8_t> png = small_png();
  ASSERT_FALSE(png_chunk_problem(png).has_value()) << *png_chunk_problem(png);
  for (size_t cut = 8; cut < png.size(); ++cut) {
    const std::optional<std::string> problem =
        png_chunk_problem(std::span<const uint8_t>(png).first(cut));
    ASSERT_TRUE(problem.has_value()) << "cut at " << cut;
    EXPECT_NE(problem->find("cut short"), std::string::npos) << *problem;
  }
  for (size_t at = 8; at < png.size(); ++at) {
    std::vector<uint8_t> changed = png;
    changed[at] ^= 0x10;
    EXPECT_TRUE(png_chunk_problem(changed).has_value()) << "byte " << at;
  }
}

}  // namespace
}  // namespace kinray
