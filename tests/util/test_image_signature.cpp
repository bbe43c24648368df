// The formats kinray lets OpenCV decode, told apart by their first bytes (util/image_signature.h).
#include "util/image_signature.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace kinray {
namespace {

ImageSignature of(std::string_view bytes) {
  return image_signature({reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size()});
}

TEST(ImageSignature, TellsTheFormatsOpenCvMayDecodeByTheirFirstBytes) {
  using namespace std::string_view_literals;
  EXPECT_EQ(of("\x89PNG\r\n\x1a\n\0\0\0\rIHDR"sv), ImageSignature::png);
  EXPECT_EQ(of("\xff\xd8\xff\xe0\0\x10JFIF"sv), ImageSignature::jpeg);
  EXPECT_EQ(of("BM6\0\0\0"sv), ImageSignature::bmp);
  EXPECT_EQ(of("II*\0\x08\0\0\0"sv), ImageSignature::tiff);
  EXPECT_EQ(of("MM\0*\0\0\0\x08"sv), ImageSignature::tiff);
  EXPECT_EQ(of("P6\n4 4\n255\n"sv), ImageSignature::pnm);
  EXPECT_EQ(of("P3 2 2 255"sv), ImageSignature::pnm);
  EXPECT_EQ(of("RIFF\x24\0\0\0WEBPVP8 "sv), ImageSignature::webp);
  for (const ImageSignature s : {ImageSignature::png, ImageSignature::jpeg, ImageSignature::bmp,
                                 ImageSignature::tiff, ImageSignature::pnm, ImageSignature::webp})
    EXPECT_TRUE(opencv_may_decode(s));
}

TEST(ImageSignature, TheDecodersThatAbortOnBadInputAreNotReached) {
  using namespace std::string_view_literals;
  // The JPEG 2000 codestream with a DICOM tag in it that aborted the fuzzed depth reader in gdcm,
  // OpenEXR's magic, a JPEG 2000 file box, a DICOM preamble, a PAM file, a truncated PNG.
  for (const std::string_view bytes :
       {"\xff\x4f\xff\x01\0\0\0\x51"sv, "\x76\x2f\x31\x01\x02\0\0\0"sv,
        "\0\0\0\x0cjP  \r\n\x87\n"sv, "DICM"sv, "P7\nWIDTH 4\n"sv, "\x89PNG\r\n"sv, ""sv,
        "RIFF\x24\0\0\0WAVEfmt "sv, "P8\n"sv}) {
    EXPECT_EQ(of(bytes), ImageSignature::other) << std::string(bytes);
    EXPECT_FALSE(opencv_may_decode(of(bytes)));
  }
  EXPECT_EQ(image_signature_name(ImageSignature::other), "an unsupported format");
}

TEST(ImageSignature, OfAFileReadsItsFirstBytes) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() /
                                    ("kinray_signature_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "short.png", std::ios::binary) << "\x89PN";
  std::ofstream(dir / "tiny.tiff", std::ios::binary) << std::string("II*\0", 4);
  EXPECT_EQ(image_signature_of_file(dir / "short.png"), ImageSignature::other);
  EXPECT_EQ(image_signature_of_file(dir / "tiny.tiff"), ImageSignature::tiff);
  EXPECT_EQ(image_signature_of_file(dir / "absent.png"), ImageSignature::other);
  EXPECT_EQ(image_signature_of_file("/usr/share/assimp/models/OBJ/wal67ar_small.jpg"),
            ImageSignature::jpeg);
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace kinray
