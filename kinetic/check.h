#pragma once
// Invariant checks (pbrt style): KINRAY_CHECK is always on, KINRAY_DCHECK only in debug builds.

#include <cstdio>
#include <cstdlib>

namespace kinray::detail {
[[noreturn]] inline void check_failed(const char* file, int line, const char* condition,
                                      const char* message) {
  std::fprintf(stderr, "%s:%d: KINRAY_CHECK failed: %s%s%s\n", file, line, condition,
               message ? " -- " : "", message ? message : "");
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

#ifdef NDEBUG
/// Debug-only check; compiles to nothing (the condition is not evaluated) when NDEBUG is set.
#define KINRAY_DCHECK(cond) \
  do {                      \
  } while (false && (cond))
#else
#define KINRAY_DCHECK(cond) KINRAY_CHECK(cond)
#endif
