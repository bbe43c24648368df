#include "tools/cli/vector_flag.h"

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace kinray {

std::optional<Vec3> parse_vector3(const std::string& text) {
  Vec3 out;
  size_t start = 0;
  for (int c = 0; c < 3; ++c) {
    const size_t comma = c < 2 ? text.find(',', start) : text.size();
    if (comma == std::string::npos) return std::nullopt;
    const std::string item = text.substr(start, comma - start);
    if (item.empty() || std::isspace(static_cast<unsigned char>(item.front()))) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(item.c_str(), &end);
    if (errno != 0 || end != item.c_str() + item.size() || !std::isfinite(x)) return std::nullopt;
    out[c] = x;
    start = comma + 1;
  }
  return out;
}

}  // namespace kinray
