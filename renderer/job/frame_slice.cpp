#include "renderer/job/frame_slice.h"

#include <charconv>

#include "util/input_error.h"

namespace kinray {
namespace {

bool parse_count(const std::string& text, size_t& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return !text.empty() && error == std::errc() && end == text.data() + text.size();
}

/// "X<separator>Y" as two non-negative integers.
bool parse_pair(const std::string& text, char separator, std::pair<size_t, size_t>& pair) {
  const size_t at = text.find(separator);
  return at != std::string::npos && parse_count(text.substr(0, at), pair.first) &&
         parse_count(text.substr(at + 1), pair.second);
}

}  // namespace

std::pair<size_t, size_t> parse_chunk(const std::string& text) {
  std::pair<size_t, size_t> chunk;
  if (!parse_pair(text, '/', chunk))
    throw InputError("--chunk",
                     "expected I/N with two positive integers, e.g. 3/10, got '" + text + "'");
  if (chunk.second < 1 || chunk.first < 1 || chunk.first > chunk.second)
    throw InputError("--chunk", "I must lie in 1..N, got '" + text + "'");
  return chunk;
}

std::pair<size_t, size_t> parse_frame_range(const std::string& text) {
  std::pair<size_t, size_t> range;
  if (!parse_pair(text, ':', range))
    throw InputError("--frame-range",
                     "expected A:B with two frame indices, e.g. 0:99, got '" + text + "'");
  if (range.first > range.second)
    throw InputError("--frame-range", "A must not exceed B, got '" + text + "'");
  return range;
}

FrameSlice frame_slice(const std::string& chunk, const std::string& range, size_t frame_count) {
  if (!chunk.empty() && !range.empty())
    throw InputError("--chunk/--frame-range", "give at most one of them");
  if (!chunk.empty()) {
    const auto [i, n] = parse_chunk(chunk);
    const FrameSlice slice{(i - 1) * frame_count / n, i * frame_count / n};
    if (slice.size() == 0)
      throw InputError("--chunk", "chunk " + chunk + " holds no frame: the schedule has only " +
                                      std::to_string(frame_count) + " frames");
    return slice;
  }
  if (!range.empty()) {
    const auto [a, b] = parse_frame_range(range);
    if (b >= frame_count)
      throw InputError("--frame-range", "frame " + std::to_string(b) +
                                            " is past the last frame of the schedule (" +
                                            std::to_string(frame_count - 1) + ")");
    return {a, b + 1};
  }
  return {0, frame_count};
}

}  // namespace kinray
