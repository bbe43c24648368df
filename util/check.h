#pragma once
// Invariant checks (pbrt style): KINRAY_CHECK is always on, KINRAY_DCHECK only in debug builds.

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <type_traits>

namespace kinray::detail {
[[noreturn]] inline void check_failed(const char* file, int line, const char* condition,
                                      const char* message) {
  std::fprintf(stderr, "%s:%d: KINRAY_CHECK failed: %s%s%s\n", file, line, condition,
               message ? " -- " : "", message ? message : "");
  std::fflush(stderr);
  std::abort();
}

/// A value of a failed comparison check, as the report shows it (numbers, enums, pointers).
template <class T>
void print_check_value(const T& value) {
  if constexpr (std::is_enum_v<T>) {
    std::fprintf(stderr, "%lld", static_cast<long long>(value));
  } else if constexpr (std::is_same_v<T, bool>) {
    std::fprintf(stderr, "%s", value ? "true" : "false");
  } else if constexpr (std::is_floating_point_v<T>) {
    std::fprintf(stderr, "%.17g", static_cast<double>(value));
  } else if constexpr (std::is_integral_v<T> && std::is_signed_v<T>) {
    std::fprintf(stderr, "%lld", static_cast<long long>(value));
  } else if constexpr (std::is_integral_v<T>) {
    std::fprintf(stderr, "%llu", static_cast<unsigned long long>(value));
  } else if constexpr (std::is_pointer_v<T>) {
    std::fprintf(stderr, "%p", static_cast<const void*>(value));
  } else {
    std::fprintf(stderr, "(not printable)");
  }
}

/// A failed KINRAY_CHECK_EQ and kin: the expression and both values, then abort.
template <class A, class B>
[[noreturn]] void check_compare_failed(const char* file, int line, const char* condition,
                                       const A& a, const B& b) {
  std::fprintf(stderr, "%s:%d: KINRAY_CHECK failed: %s (", file, line, condition);
  print_check_value(a);
  std::fprintf(stderr, " vs ");
  print_check_value(b);
  std::fprintf(stderr, ")\n");
  std::fflush(stderr);
  std::abort();
}
}  // namespace kinray::detail

/// Always on: on failure prints file:line and the condition to stderr, then std::abort().
#define KINRAY_CHECK(cond)                                                        \
  do {                                                                            \
    if (!(cond)) [[unlikely]]                                                     \
      ::kinray::detail::check_failed(__FILE__, __LINE__, #cond, nullptr);         \
  } while (false)

/// As KINRAY_CHECK, with a message (a const char*) appended to the report.
#define KINRAY_CHECK_MSG(cond, msg)                                               \
  do {                                                                            \
    if (!(cond)) [[unlikely]]                                                     \
      ::kinray::detail::check_failed(__FILE__, __LINE__, #cond, (msg));           \
  } while (false)

/// Comparison checks: as KINRAY_CHECK(a op b), and the report shows both values,
/// "KINRAY_CHECK failed: m_size > 0 (0 vs 0)". Each operand is evaluated once.
#define KINRAY_CHECK_OP(op, a, b)                                                          \
  do {                                                                                     \
    const auto& kinray_check_a = (a);                                                      \
    const auto& kinray_check_b = (b);                                                      \
    if (!(kinray_check_a op kinray_check_b)) [[unlikely]]                                  \
      ::kinray::detail::check_compare_failed(__FILE__, __LINE__, #a " " #op " " #b,        \
                                             kinray_check_a, kinray_check_b);              \
  } while (false)
#define KINRAY_CHECK_EQ(a, b) KINRAY_CHECK_OP(==, a, b)
#define KINRAY_CHECK_NE(a, b) KINRAY_CHECK_OP(!=, a, b)
#define KINRAY_CHECK_LT(a, b) KINRAY_CHECK_OP(<, a, b)
#define KINRAY_CHECK_LE(a, b) KINRAY_CHECK_OP(<=, a, b)
#define KINRAY_CHECK_GT(a, b) KINRAY_CHECK_OP(>, a, b)
#define KINRAY_CHECK_GE(a, b) KINRAY_CHECK_OP(>=, a, b)

#ifdef NDEBUG
/// Debug-only check; compiles to nothing (the condition is not evaluated) when NDEBUG is set.
#define KINRAY_DCHECK(cond) \
  do {                      \
  } while (false && (cond))
#define KINRAY_DCHECK_OP(op, a, b) \
  do {                             \
  } while (false && ((a)op(b)))
#else
#define KINRAY_DCHECK(cond) KINRAY_CHECK(cond)
#define KINRAY_DCHECK_OP(op, a, b) KINRAY_CHECK_OP(op, a, b)
#endif
#define KINRAY_DCHECK_EQ(a, b) KINRAY_DCHECK_OP(==, a, b)
#define KINRAY_DCHECK_NE(a, b) KINRAY_DCHECK_OP(!=, a, b)
