#include "tools/cli/frame_slice_flags.h"

#include <charconv>
#include <utility>

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

/// An OptionError of validate() as the flag's InputError.
template <class Check>
void checked(const char* flag, Check check) {
  try {
    check();
  } catch (const OptionError& error) {
    throw InputError(flag, error.message());
  }
}

}  // namespace

FrameChunk parse_chunk(const std::string& text) {
  std::pair<size_t, size_t> pair;
  if (!parse_pair(text, '/', pair))
    throw InputError("--chunk",
                     "expected I/N with two positive integers, e.g. 3/10, got '" + text + "'");
  const FrameChunk chunk{pair.first, pair.second};
  checked("--chunk", [&] { validate(chunk, std::nullopt); });
  return chunk;
}

FrameRange parse_frame_range(const std::string& text) {
  std::pair<size_t, size_t> pair;
  if (!parse_pair(text, ':', pair))
    throw InputError("--frame-range",
                     "expected A:B with two frame indices, e.g. 0:99, got '" + text + "'");
  const FrameRange range{pair.first, pair.second};
  checked("--frame-range", [&] { validate(std::nullopt, range); });
  return range;
}

}  // namespace kinray
