#pragma once
// `--size WxH` (and bench's `--sizes`) and `--aov id,depth`: the image flags of `render`, `diff`
// and `bench`.
#include <string>
#include <utility>
#include <vector>

namespace kinray {

/// Parses "WxH" into width and height (1..kMaxImageSide each). Throws InputError naming `flag`.
[[nodiscard]] std::pair<int, int> parse_size(const std::string& text, const char* flag = "--size");
/// Parses "id,depth" (any of id, depth; no repeats). Throws InputError naming --aov.
[[nodiscard]] std::vector<std::string> parse_aov(const std::string& text);

}  // namespace kinray
