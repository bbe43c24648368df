#include "scenes/mesh_file.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "util/input_error.h"

namespace kinray {

void check_mesh_coordinate(double value, const char* what, const std::string& where) {
  if (!std::isfinite(value))
    throw InputError(where, std::string("coordinate ") + what + " is NaN or infinite");
  if (std::abs(value) > kMaxCoordinate) {
    char text[160];
    std::snprintf(text, sizeof text,
                  "coordinate %s = %g lies beyond +-1e15, which the float references cannot trace",
                  what, value);
    throw InputError(where, text);
  }
}

std::string read_mesh_bytes(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path, "cannot be opened for reading");
  std::ostringstream bytes;
  bytes << file.rdbuf();
  if (file.bad()) throw InputError(path, "cannot be read");
  return std::move(bytes).str();
}

std::vector<std::string_view> split_words(std::string_view line) {
  std::vector<std::string_view> out;
  const auto space = [](char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
  };
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && space(line[i])) ++i;
    const size_t begin = i;
    while (i < line.size() && !space(line[i])) ++i;
    if (i > begin) out.push_back(line.substr(begin, i - begin));
  }
  return out;
}

void append_fan(const std::vector<uint32_t>& polygon, std::vector<Triangle>& triangles) {
  for (size_t k = 1; k + 1 < polygon.size(); ++k)
    triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
}

}  // namespace kinray
