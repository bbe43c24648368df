#pragma once
// A value of a JSON scene file together with where it came from: the file and its JSON pointer.
// Every accessor checks the type and throws InputError naming both, so that a malformed file
// gets one line saying where and what.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "scenes/scene.h"
#include "util/input_error.h"

namespace kinray {

/// `key` as a JSON pointer token (RFC 6901: '~' and '/' escaped).
[[nodiscard]] std::string escape_pointer_token(const std::string& key);
/// A JSON value's type for an error message (null is how JSON writers store NaN and infinity).
[[nodiscard]] std::string json_type_name(const nlohmann::json& value);

/// A JSON value and where it is: the file and its JSON pointer.
class JsonNode {
 public:
  JsonNode(const nlohmann::json& value, const std::string& file, std::string pointer)
      : m_value(&value), m_file(&file), m_pointer(std::move(pointer)) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(m_pointer.empty() ? *m_file : *m_file + ": " + m_pointer, problem);
  }
  [[nodiscard]] const std::string& pointer() const { return m_pointer; }
  [[nodiscard]] const nlohmann::json& value() const { return *m_value; }

  /// Requires an object whose keys are all in `allowed`.
  void expect_object(std::initializer_list<const char*> allowed) const {
    if (!m_value->is_object()) fail("expected an object, got " + json_type_name(*m_value));
    for (const auto& item : m_value->items()) {
      if (std::find_if(allowed.begin(), allowed.end(),
                       [&](const char* a) { return item.key() == a; }) != allowed.end())
        continue;
      std::string valid;
      for (const char* a : allowed) valid += (valid.empty() ? "" : ", ") + std::string(a);
      child(item.key())
          .fail("unknown key '" + item.key() + "'; the keys allowed here are " + valid);
    }
  }
  [[nodiscard]] bool has(const char* key) const {
    return m_value->is_object() && m_value->contains(key);
  }
  [[nodiscard]] JsonNode at(const char* key) const {
    if (!m_value->is_object()) fail("expected an object, got " + json_type_name(*m_value));
    if (!m_value->contains(key)) fail(std::string("missing key '") + key + "'");
    return child(key);
  }
  [[nodiscard]] std::optional<JsonNode> find(const char* key) const {
    if (!has(key)) return std::nullopt;
    return child(key);
  }
  [[nodiscard]] size_t size() const {
    if (!m_value->is_array()) fail("expected an array, got " + json_type_name(*m_value));
    return m_value->size();
  }
  /// Requires an array of `n` elements.
  void expect_size(size_t n) const {
    if (size() != n)
      fail("expected an array of " + std::to_string(n) + " elements, got " +
           std::to_string(size()));
  }
  [[nodiscard]] JsonNode operator[](size_t i) const {
    return JsonNode((*m_value)[i], *m_file, m_pointer + "/" + std::to_string(i));
  }

  [[nodiscard]] double number() const {
    if (!m_value->is_number()) fail("expected a number, got " + json_type_name(*m_value));
    const double x = m_value->get<double>();
    if (!std::isfinite(x)) fail("expected a finite number");
    return x;
  }
  [[nodiscard]] double positive() const {
    const double x = number();
    if (!(x > 0)) fail("expected a number > 0, got " + std::to_string(x));
    return x;
  }
  [[nodiscard]] uint64_t unsigned_integer() const {
    if (!m_value->is_number_integer()) fail("expected an integer, got " + json_type_name(*m_value));
    if (m_value->is_number_integer() && !m_value->is_number_unsigned())
      fail("expected an integer >= 0");
    return m_value->get<uint64_t>();
  }
  /// An integer in [lo, hi].
  [[nodiscard]] int integer(int lo, int hi) const {
    if (!m_value->is_number_integer()) fail("expected an integer, got " + json_type_name(*m_value));
    const int64_t x = m_value->get<int64_t>();
    if (x < lo || x > hi)
      fail("expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
           std::to_string(x));
    return int(x);
  }
  [[nodiscard]] std::string string() const {
    if (!m_value->is_string()) fail("expected a string, got " + json_type_name(*m_value));
    return m_value->get<std::string>();
  }
  [[nodiscard]] Vec3 vec3() const {
    expect_size(3);
    return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
  }

 private:
  [[nodiscard]] JsonNode child(const std::string& key) const {
    return JsonNode((*m_value)[key], *m_file, m_pointer + "/" + escape_pointer_token(key));
  }
  const nlohmann::json* m_value;
  const std::string* m_file;
  std::string m_pointer;
};

}  // namespace kinray
