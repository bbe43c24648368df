#include "tools/cli/light_flag.h"

#include "tools/cli/vector_flag.h"
#include "util/input_error.h"

namespace kinray {
namespace {

[[noreturn]] void fail(const std::string& text, const std::string& problem) {
  throw InputError("--light", problem + " in '" + text +
                                  "' (expected point:X,Y,Z[:R,G,B] or dir:X,Y,Z[:R,G,B])");
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
  const std::optional<Vec3> xyz = parse_vector3(where);
  if (!xyz)
    fail(text, std::string(light.kind == Light::Kind::point ? "the position" : "the direction") +
                   " must be three finite numbers X,Y,Z");
  if (light.kind == Light::Kind::point) {
    light.position = *xyz;
  } else {
    if (!(xyz->norm() > 0)) fail(text, "the direction must not be zero");
    light.direction = xyz->normalized();
  }
  if (second != std::string::npos) {
    const std::optional<Vec3> rgb = parse_vector3(text.substr(second + 1));
    if (!rgb || (rgb->array() < 0).any())
      fail(text, "the colour must be three finite numbers R,G,B >= 0");
    light.color = rgb->cast<float>();
  }
  if (const std::optional<std::string> problem = light_problem(light)) fail(text, *problem);
  return light;
}

}  // namespace kinray
