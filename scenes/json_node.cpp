#include "scenes/json_node.h"

namespace kinray {

std::string escape_pointer_token(const std::string& key) {
  std::string token;
  for (char c : key) {
    if (c == '~')
      token += "~0";
    else if (c == '/')
      token += "~1";
    else
      token += c;
  }
  return token;
}

std::string json_type_name(const nlohmann::json& value) {
  return value.is_null() ? "null (which is how JSON writers store NaN and infinity)"
                         : std::string(value.type_name());
}

}  // namespace kinray
