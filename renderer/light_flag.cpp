#include "renderer/light_flag.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>

#include "scenes/error.h"

namespace kinray {
namespace {

[[noreturn]] void fail(const std::string& text, const std::string& problem) {
  throw InputError("--light", problem + " in '" + text +
                                  "' (expected point:X,Y,Z[:R,G,B] or dir:X,Y,Z[:R,G,B])");
}

/// Three finite numbers separated by commas.
bool parse_triple(const std::string& field, Vec3& out) {
  size_t start = 0;
  for (int c = 0; c < 3; ++c) {
    const size_t comma = c < 2 ? field.find(',', start) : field.size();
    if (comma == std::string::npos) return false;
    const std::string item = field.substr(start, comma - start);
    if (item.empty() || std::isspace(static_cast<unsigned char>(item.front()))) return false;
    char* end = nullptr;
    errno = 0;
    const double x = std::strtod(item.c_str(), &end);
    if (errno != 0 || end != item.c_str() + item.size() || !std::isfinite(x)) return false;
    out[c] = x;
    start = comma + 1;
  }
  return true;
}

}  // namespace

Light parse_light_flag(const std::string& text) {
  const size_t first = text.find(':');
  if (first == std::string::npos) fail(text, "no kind");
  const std::string kind = text.substr(0, first);
  Light light;
  if (kind == "point")
    light.kind = Light::Kind::point;
  else if (kind == "dir")
    light.kind = Light::Kind::directional;
  else
    fail(text, "unknown kind '" + kind + "'");
  const size_t second = text.find(':', first + 1);
  const std::string where =
      text.substr(first + 1, second == std::string::npos ? std::string::npos : second - first - 1);
  Vec3 xyz;
  if (!parse_triple(where, xyz))
    fail(text, std::string(light.kind == Light::Kind::point ? "the position" : "the direction") +
                   " must be three finite numbers X,Y,Z");
  if (light.kind == Light::Kind::point) {
    light.position = xyz;
  } else {
    if (!(xyz.norm() > 0)) fail(text, "the direction must not be zero");
    light.direction = xyz.normalized();
  }
  if (second != std::string::npos) {
    Vec3 rgb;
    if (!parse_triple(text.substr(second + 1), rgb) || (rgb.array() < 0).any())
      fail(text, "the colour must be three finite numbers R,G,B >= 0");
    light.color = rgb.cast<float>();
  }
  return light;
}

}  // namespace kinray
