// PNG colour frames, lossless ID and depth buffers: what is written reads back bit for bit, and
// files appear whole or not at all.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "renderer/output/image_io.h"
#include "scenes/texture_image.h"
#include "util/input_error.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

class ImageIo : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = fs::temp_directory_path() /
            ("kinray_image_io_" +
             std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override { fs::remove_all(m_dir); }
  [[nodiscard]] std::string path(const std::string& name) const { return (m_dir / name).string(); }
  [[nodiscard]] size_t file_count() const {
    return size_t(std::distance(fs::directory_iterator(m_dir), fs::directory_iterator()));
  }
  fs::path m_dir;
};

/// A frame with background, small and large ids (prims using all 32 bits), and assorted depths.
Frame random_frame(int width, int height, unsigned seed) {
  std::mt19937 random(seed);
  Frame frame;
  frame.resize(width, height);
  for (size_t p = 0; p < frame.pixel_count(); ++p) {
    if (random() % 5 == 0) continue;  // background: kNoHit, +inf
    frame.object[p] = random() % 3 == 0 ? uint32_t(random() % 65534) : uint32_t(random() % 7);
    frame.prim[p] = random() % 2 ? uint32_t(random()) : uint32_t(random() % 1000);
    frame.depth[p] = std::ldexp(float(random() % 1000000 + 1), int(random() % 40) - 30);
    frame.color[p] = Color(float(random() % 1000) / 999.0f, float(random() % 1000) / 999.0f, 0.25f);
  }
  frame.depth[1] = std::numeric_limits<float>::denorm_min();
  frame.object[1] = 0;
  frame.prim[1] = 0xFFFFFFFEu;
  return frame;
}

TEST_F(ImageIo, IdBufferRoundTripsExactly) {
  const Frame written = random_frame(37, 23, 1);
  write_id_png(path("id_00000.png"), written);
  Frame read;
  read_id_png(path("id_00000.png"), read);
  EXPECT_EQ(read.width, 37);
  EXPECT_EQ(read.height, 23);
  EXPECT_EQ(read.object, written.object);
  EXPECT_EQ(read.prim, written.prim);
  EXPECT_EQ(file_count(), 1u) << "no temporary file may be left behind";
}

TEST_F(ImageIo, DepthBufferRoundTripsBitForBit) {
  const Frame written = random_frame(41, 19, 2);
  write_depth_tiff(path("depth_00000.tiff"), written);
  Frame read;
  read_depth_tiff(path("depth_00000.tiff"), read);
  ASSERT_EQ(read.depth.size(), written.depth.size());
  EXPECT_EQ(
      std::memcmp(read.depth.data(), written.depth.data(), written.depth.size() * sizeof(float)),
      0);
  EXPECT_TRUE(std::isinf(read.depth[0]) || read.depth[0] == written.depth[0]);
}

TEST_F(ImageIo, ReadingIdThenDepthFillsOneFrame) {
  const Frame written = random_frame(16, 16, 3);
  write_id_png(path("id.png"), written);
  write_depth_tiff(path("depth.tiff"), written);
  Frame read;
  read_id_png(path("id.png"), read);
  read_depth_tiff(path("depth.tiff"), read);
  EXPECT_EQ(read.object, written.object);
  EXPECT_EQ(read.prim, written.prim);
  EXPECT_EQ(
      std::memcmp(read.depth.data(), written.depth.data(), written.depth.size() * sizeof(float)),
      0);
}

TEST_F(ImageIo, ColourPngReadsBackAsWritten) {
  const Frame frame = random_frame(29, 31, 4);
  write_color_png(path("frame_00000.png"), frame);
  const cv::Mat read = read_color_png(path("frame_00000.png"));
  const cv::Mat expected = color_image(frame);
  ASSERT_EQ(read.size(), expected.size());
  EXPECT_EQ(cv::norm(read, expected, cv::NORM_INF), 0.0);
  // Pixel (3, 2): BGR order, sRGB-encoded linear colour.
  const Color c = frame.color[frame.index(3, 2)];
  const cv::Vec3b v = read.at<cv::Vec3b>(2, 3);
  EXPECT_EQ(v[2], linear_to_srgb8(c.x()));
  EXPECT_EQ(v[1], linear_to_srgb8(c.y()));
  EXPECT_EQ(v[0], linear_to_srgb8(c.z()));
}

TEST(Srgb, EncodesTheStandardCurve) {
  EXPECT_EQ(linear_to_srgb8(0.0f), 0);
  EXPECT_EQ(linear_to_srgb8(-1.0f), 0);
  EXPECT_EQ(linear_to_srgb8(std::nanf("")), 0);
  EXPECT_EQ(linear_to_srgb8(1.0f), 255);
  EXPECT_EQ(linear_to_srgb8(7.0f), 255);
  EXPECT_EQ(linear_to_srgb8(0.5f), 188);   // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354 -> 187.5 -> 188
  EXPECT_EQ(linear_to_srgb8(0.18f), 118);  // middle grey: 0.4614 * 255 = 117.66
  EXPECT_EQ(linear_to_srgb8(0.001f), 3);   // linear segment: 12.92 * 0.001 * 255 = 3.29
  for (int code = 0; code < 256; ++code)
    EXPECT_EQ(linear_to_srgb8(srgb_to_linear(uint8_t(code))), code);
  for (float x = 0; x < 1; x += 1e-3f) EXPECT_LE(linear_to_srgb8(x), linear_to_srgb8(x + 1e-3f));
}

// The encoder's bucket table against the curve's definition: the code of x is the number of
// decision points srgb_decode((c + 0.5) / 255) at or below it. Checked on both sides of every
// decision point (where a wrong bucket would show first), at the ends of the range and at a
// million random floats in (0, 1), spread over every exponent.
TEST(Srgb, BucketTableIsTheDefinition) {
  std::vector<float> points;
  for (int c = 0; c < 255; ++c) points.push_back(srgb_decode((c + 0.5) / 255.0));
  auto definition = [&](float x) {
    if (!(x > 0.0f)) return 0;
    return int(std::upper_bound(points.begin(), points.end(), x) - points.begin());
  };
  std::vector<float> xs = {std::numeric_limits<float>::denorm_min(), 1e-30f, 0.99999994f, 1.0f,
                           std::numeric_limits<float>::infinity()};
  for (const float p : points)
    for (const float x : {std::nextafter(p, 0.0f), p, std::nextafter(p, 2.0f)}) xs.push_back(x);
  std::mt19937 random(7);
  std::uniform_int_distribution<uint32_t> bits(1, 0x3F7FFFFF);  // the positive floats below 1
  for (int k = 0; k < 1'000'000; ++k) xs.push_back(std::bit_cast<float>(bits(random)));
  for (const float x : xs) ASSERT_EQ(int(linear_to_srgb8(x)), definition(x)) << "x = " << x;
}

TEST_F(ImageIo, BadFilesAreInputErrorsNamingThePath) {
  Frame frame;
  try {
    read_id_png(path("missing.png"), frame);
    FAIL() << "a missing file must throw";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("missing.png"), std::string::npos) << e.what();
  }
  const Frame written = random_frame(8, 8, 5);
  write_color_png(path("colour.png"), written);
  EXPECT_THROW(read_id_png(path("colour.png"), frame), InputError);
  try {
    read_depth_tiff(path("colour.png"), frame);
    FAIL() << "a PNG is not a depth TIFF";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("colour.png: not a TIFF file (it is a PNG)"),
              std::string::npos)
        << e.what();
  }
  // A file named .tiff whose bytes another decoder claims (a JPEG 2000 codestream holding a DICOM
  // tag, found by fuzzing: gdcm aborted the process on it) is refused before any decoder sees it.
  write_file_atomically(path("dicom.tiff"), std::string("\xff\x4f\xff\x01\0\0\0\x51" "DICM", 12));
  EXPECT_THROW(read_depth_tiff(path("dicom.tiff"), frame), InputError);
  write_file_atomically(path("garbage.png"), "not a png at all");
  EXPECT_THROW((void)read_color_png(path("garbage.png")), InputError);
  // A write that fails is the machine's failure (exit status 1), not bad input: commands check
  // their output paths before they start (output_check.h).
  try {
    write_color_png(path("no/such/folder/frame.png"), written);
    FAIL() << "an impossible write must throw";
  } catch (const InputError& e) {
    ADD_FAILURE() << "a failed write is not bad input: " << e.what();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("frame.png: cannot write"), std::string::npos) << e.what();
  }
}

TEST_F(ImageIo, AtomicWriteReplacesWholeFiles) {
  write_file_atomically(path("a.txt"), "first");
  write_file_atomically(path("a.txt"), "second version");
  std::FILE* file = std::fopen(path("a.txt").c_str(), "rb");
  ASSERT_NE(file, nullptr);
  char buffer[64] = {};
  const size_t n = std::fread(buffer, 1, sizeof buffer, file);
  std::fclose(file);
  EXPECT_EQ(std::string(buffer, n), "second version");
  EXPECT_EQ(file_count(), 1u);
}

}  // namespace
}  // namespace kinray
