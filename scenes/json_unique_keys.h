#pragma once
// JSON allows an object to give a key twice, and nlohmann::json keeps the last value: a scene
// file with two "shot" keys would lose the first without a word. kinray's readers take JSON
// through this parse, which refuses a repeated key and names where it is.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace kinray {

/// A key given twice in one object: the object's JSON pointer ("" for the document) and the key.
struct DuplicateJsonKey : std::runtime_error {
  DuplicateJsonKey(std::string object_pointer, std::string repeated)
      : std::runtime_error("key '" + repeated + "' is given twice"),
        pointer(std::move(object_pointer)),
        key(std::move(repeated)) {}
  std::string pointer, key;
};

/// nlohmann::json::parse, but throws DuplicateJsonKey at the first key an object repeats.
/// Syntax errors are nlohmann's own exceptions, as from json::parse.
[[nodiscard]] nlohmann::json parse_json_with_unique_keys(const std::string& text);

}  // namespace kinray
