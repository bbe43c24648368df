#include "scenes/json_unique_keys.h"

#include <unordered_set>
#include <vector>

namespace kinray {
namespace {

/// A JSON pointer's reference token: '~' and '/' escaped (RFC 6901).
std::string pointer_token(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else
      out += c;
  }
  return out;
}

/// An object or array being parsed: its pointer, and what names its next member.
struct OpenValue {
  bool array = false;
  std::string pointer;
  std::string key;                       ///< an object's last key
  size_t next_index = 0;                 ///< an array's next element
  std::unordered_set<std::string> keys;  ///< an object's keys so far
};

}  // namespace

nlohmann::json parse_json_with_unique_keys(const std::string& text) {
  using Event = nlohmann::json::parse_event_t;
  std::vector<OpenValue> open;
  // The pointer of the value that starts now, inside the innermost open value.
  const auto member_pointer = [&]() -> std::string {
    if (open.empty()) return "";
    OpenValue& parent = open.back();
    if (parent.array) return parent.pointer + "/" + std::to_string(parent.next_index++);
    return parent.pointer + "/" + pointer_token(parent.key);
  };
  const nlohmann::json::parser_callback_t callback = [&](int, Event event, nlohmann::json& parsed) {
    switch (event) {
      case Event::object_start:
      case Event::array_start: {
        OpenValue value;
        value.array = event == Event::array_start;
        value.pointer = member_pointer();
        open.push_back(std::move(value));
        break;
      }
      case Event::object_end:
      case Event::array_end:
        open.pop_back();
        break;
      case Event::key: {
        OpenValue& object = open.back();
        object.key = parsed.get<std::string>();
        if (!object.keys.insert(object.key).second)
          throw DuplicateJsonKey(object.pointer, object.key);
        break;
      }
      case Event::value:  // a number, string, boolean or null (compound values end above)
        if (!open.empty() && open.back().array) ++open.back().next_index;
        break;
    }
    return true;
  };
  return nlohmann::json::parse(text, callback);
}

}  // namespace kinray
