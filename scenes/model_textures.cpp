#include "scenes/model_textures.h"

#include <assimp/scene.h>
#include <assimp/texture.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <span>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <system_error>

#include "scenes/model_assimp.h"
#include "scenes/model_tga.h"
#include "scenes/texture_image.h"
#include "util/image_signature.h"

namespace kinray {

namespace {

std::optional<Texture> from_bgr(const cv::Mat& image, const std::string& name,
                                const std::string& where) {
  if (image.empty() || image.type() != CV_8UC3) {
    warn_repair(where, "texture '" + name + "' could not be decoded; using the base colour alone");
    return std::nullopt;
  }
  if (size_t(image.cols) * size_t(image.rows) > kMaxTexels) {
    warn_repair(where, "texture '" + name +
                           "' is larger than 8192 x 8192 texels; using the base colour alone");
    return std::nullopt;
  }
  return texture_from_bgr(image, name);
}

std::optional<Texture> from_embedded(const aiTexture& embedded, const std::string& name,
                                     const std::string& where) {
  if (embedded.pcData == nullptr || embedded.mWidth == 0) {
    warn_repair(where, "embedded texture '" + name + "' is empty; using the base colour alone");
    return std::nullopt;
  }
  if (embedded.mHeight == 0) {  // a compressed file (png, jpg, tga, ...) of mWidth bytes
    const auto* data = reinterpret_cast<const uint8_t*>(embedded.pcData);
    const std::span<const uint8_t> bytes(data, embedded.mWidth);
    cv::Mat image;
    if (opencv_may_decode(image_signature(bytes))) {
      try {
        image = cv::imdecode(
            cv::Mat(1, int(embedded.mWidth), CV_8UC1, const_cast<uint8_t*>(data)),
            cv::IMREAD_COLOR);
      } catch (const cv::Exception&) {
        image = cv::Mat();
      }
    }
    if (image.empty()) image = decode_tga(bytes);
    return from_bgr(image, name, where);
  }
  if (size_t(embedded.mWidth) * size_t(embedded.mHeight) > kMaxTexels)
    return from_bgr(cv::Mat(), name, where);
  cv::Mat image(int(embedded.mHeight), int(embedded.mWidth), CV_8UC3);
  for (unsigned y = 0; y < embedded.mHeight; ++y)
    for (unsigned x = 0; x < embedded.mWidth; ++x) {
      const aiTexel& texel = embedded.pcData[size_t(y) * embedded.mWidth + x];
      image.at<cv::Vec3b>(int(y), int(x)) = cv::Vec3b(texel.b, texel.g, texel.r);
    }
  return from_bgr(image, name, where);
}

bool is_file(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::is_regular_file(path, error);
}

}  // namespace

std::optional<Texture> read_texture(const aiScene& scene, const std::string& reference,
                                    const std::filesystem::path& model_directory,
                                    const std::string& where) {
  if (reference.empty()) return std::nullopt;
  if (reference[0] == '*' || scene.GetEmbeddedTexture(reference.c_str()) != nullptr) {
    const aiTexture* embedded = scene.GetEmbeddedTexture(reference.c_str());
    if (embedded == nullptr) {
      warn_repair(where, "names embedded texture '" + reference +
                             "', which the file does not hold; using the base colour alone");
      return std::nullopt;
    }
    return from_embedded(*embedded, reference, where);
  }
  std::string written = reference;
  for (char& c : written)
    if (c == '\\') c = '/';
  std::filesystem::path path = model_directory / std::filesystem::path(written);
  if (!is_file(path)) {
    const std::filesystem::path beside =
        model_directory / std::filesystem::path(written).filename();
    if (!is_file(beside)) {
      warn_repair(where, "texture file '" + reference + "' not found (looked for " + path.string() +
                             " and " + beside.string() + "); using the base colour alone");
      return std::nullopt;
    }
    path = beside;
  }
  cv::Mat image;
  if (opencv_may_decode(image_signature_of_file(path))) {
    try {
      image = cv::imread(path.string(), cv::IMREAD_COLOR);
    } catch (const cv::Exception&) {
      image = cv::Mat();
    }
  }
  if (image.empty()) {  // OpenCV 4.6 reads no TGA
    std::ifstream file(path, std::ios::binary);
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    image = decode_tga(bytes);
  }
  return from_bgr(image, path.string(), where);
}

}  // namespace kinray
