#pragma once
// One table of names per option enum: parsing, printing, help and JSON all read the same table,
// so a value is spelled once. The command line builds its member checks from these tables
// (tools/cli_options.h); the library takes the enums and never sees the strings.
//
//   inline constexpr std::array kFruitNames{EnumName{Fruit::kApple, "apple"}, ...};
//   enum_name(kFruitNames, Fruit::kApple) == "apple"; find_enum(kFruitNames, "apple")
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace kinray {

template <class Enum>
struct EnumName {
  Enum value;
  const char* name;
};
/// Spelled out for clang 14 (the fuzz build), which deduces no aggregate's template arguments.
template <class Enum>
EnumName(Enum, const char*) -> EnumName<Enum>;

/// The name of `value` in `table` ("?" if the table misses it, which a test rules out).
template <class Enum, size_t N>
[[nodiscard]] constexpr const char* enum_name(const std::array<EnumName<Enum>, N>& table,
                                              Enum value) {
  for (const EnumName<Enum>& entry : table)
    if (entry.value == value) return entry.name;
  return "?";
}

/// The value called `name` in `table`, if any.
template <class Enum, size_t N>
[[nodiscard]] constexpr std::optional<Enum> find_enum(const std::array<EnumName<Enum>, N>& table,
                                                      std::string_view name) {
  for (const EnumName<Enum>& entry : table)
    if (name == entry.name) return entry.value;
  return std::nullopt;
}

/// The names joined by `separator`, in table order: "list, tournament, heap".
template <class Enum, size_t N>
[[nodiscard]] std::string enum_names(const std::array<EnumName<Enum>, N>& table,
                                     std::string_view separator = ", ") {
  std::string names;
  for (const EnumName<Enum>& entry : table) {
    if (!names.empty()) names += separator;
    names += entry.name;
  }
  return names;
}

}  // namespace kinray
