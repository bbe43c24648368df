#include "tools/cli/image_flags.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>

#include "renderer/job/render_job.h"
#include "util/input_error.h"

namespace kinray {
namespace {

bool parse_int(const std::string& text, int& value) {
  if (text.empty() || !std::isdigit(static_cast<unsigned char>(text.front()))) return false;
  char* end = nullptr;
  errno = 0;
  const long parsed = std::strtol(text.c_str(), &end, 10);
  if (errno != 0 || end != text.c_str() + text.size() || parsed > 1'000'000'000L) return false;
  value = int(parsed);
  return true;
}

}  // namespace

std::pair<int, int> parse_size(const std::string& text, const char* flag) {
  const size_t x = text.find_first_of("xX");
  int width = 0, height = 0;
  if (x == std::string::npos || !parse_int(text.substr(0, x), width) ||
      !parse_int(text.substr(x + 1), height))
    throw InputError(flag,
                     "expected WxH with two positive integers, e.g. 512x512, got '" + text + "'");
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw InputError(flag, "width and height must lie in 1.." + std::to_string(kMaxImageSide) +
                               ", got '" + text + "'");
  return {width, height};
}

std::vector<std::string> parse_aov(const std::string& text) {
  std::vector<std::string> aovs;
  size_t start = 0;
  while (start <= text.size()) {
    const size_t comma = std::min(text.find(',', start), text.size());
    const std::string name = text.substr(start, comma - start);
    if (const auto problem = aov_problem(name)) throw InputError("--aov", *problem);
    if (std::find(aovs.begin(), aovs.end(), name) != aovs.end())
      throw InputError("--aov", "'" + name + "' is given twice");
    aovs.push_back(name);
    start = comma + 1;
  }
  return aovs;
}

}  // namespace kinray
