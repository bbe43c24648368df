#include "scenes/model_tga.h"

namespace kinray {

cv::Mat decode_tga(std::span<const uint8_t> bytes) {
  if (bytes.size() < 18) return {};
  const uint8_t id_length = bytes[0], colour_map_type = bytes[1], image_type = bytes[2];
  const int width = bytes[12] | (bytes[13] << 8), height = bytes[14] | (bytes[15] << 8);
  const int depth = bytes[16], descriptor = bytes[17];
  const bool run_length = image_type == 10 || image_type == 11;
  const bool grey = image_type == 3 || image_type == 11;
  if (colour_map_type != 0 || !(image_type == 2 || image_type == 3 || run_length)) return {};
  if (width == 0 || height == 0) return {};
  if (grey ? depth != 8 : (depth != 24 && depth != 32)) return {};
  const size_t pixel_bytes = size_t(depth) / 8, pixels = size_t(width) * size_t(height);
  size_t at = 18 + id_length;
  // The header's size (up to 65535 x 65535 x 4 bytes, 17 GB) is believed only as far as the data
  // can fill it: stored pixels, or run-length packets of at least 1 + pixel_bytes bytes and at
  // most 128 pixels each. Otherwise a hostile texture would allocate before being found short.
  const size_t available = bytes.size() > at ? bytes.size() - at : 0;
  if (run_length ? pixels > (available / (1 + pixel_bytes) + 1) * 128
                 : pixels * pixel_bytes > available)
    return {};

  std::vector<uint8_t> data(pixels * pixel_bytes);
  if (!run_length) {
    if (bytes.size() < at + data.size()) return {};
    std::copy(bytes.begin() + std::ptrdiff_t(at), bytes.begin() + std::ptrdiff_t(at + data.size()),
              data.begin());
  } else {
    // Packets: a header byte, then one pixel repeated (high bit set) or raw pixels, 1..128 each.
    for (size_t done = 0; done < pixels;) {
      if (at >= bytes.size()) return {};
      const uint8_t header = bytes[at++];
      const size_t count = size_t(header & 0x7f) + 1;
      if (done + count > pixels) return {};
      const size_t stored = (header & 0x80) ? pixel_bytes : count * pixel_bytes;
      if (at + stored > bytes.size()) return {};
      for (size_t i = 0; i < count; ++i)
        for (size_t b = 0; b < pixel_bytes; ++b)
          data[(done + i) * pixel_bytes + b] =
              bytes[at + ((header & 0x80) ? b : i * pixel_bytes + b)];
      at += stored;
      done += count;
    }
  }

  cv::Mat image(height, width, CV_8UC3);
  const bool top_first = (descriptor & 0x20) != 0, right_to_left = (descriptor & 0x10) != 0;
  for (int y = 0; y < height; ++y) {
    const int row = top_first ? y : height - 1 - y;
    for (int x = 0; x < width; ++x) {
      const int column = right_to_left ? width - 1 - x : x;
      const uint8_t* p = &data[(size_t(y) * size_t(width) + size_t(x)) * pixel_bytes];
      image.at<cv::Vec3b>(row, column) =
          grey ? cv::Vec3b(p[0], p[0], p[0]) : cv::Vec3b(p[0], p[1], p[2]);
    }
  }
  return image;
}

}  // namespace kinray
