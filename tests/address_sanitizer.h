#pragma once
// Whether this test binary is built with AddressSanitizer (tools/checks.sh sanitize, the fuzz
// build), for the few tests whose meaning ASan's own memory layout takes away: it reserves
// terabytes of address space for its shadow at start-up, so an address-space limit (RLIMIT_AS,
// `ulimit -v`) cannot model a machine with little memory, and freed memory stays resident in its
// quarantine. Such a test skips that part visibly (GTEST_SKIP with the reason), only here.
// GCC defines __SANITIZE_ADDRESS__; clang answers __has_feature(address_sanitizer). The suite's
// own code is compiled without instrumentation in the sanitizer build (tests/CMakeLists.txt),
// which then defines KINRAY_UNDER_ADDRESS_SANITIZER itself.

namespace kinray::test {

#if defined(KINRAY_UNDER_ADDRESS_SANITIZER)
#elif defined(__SANITIZE_ADDRESS__)
#define KINRAY_UNDER_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define KINRAY_UNDER_ADDRESS_SANITIZER 1
#endif
#endif

#ifdef KINRAY_UNDER_ADDRESS_SANITIZER
/// True in a build with AddressSanitizer.
inline constexpr bool kUnderAddressSanitizer = true;
#else
/// True in a build with AddressSanitizer.
inline constexpr bool kUnderAddressSanitizer = false;
#endif

/// Why an address-space limit is not tested under AddressSanitizer (GTEST_SKIP's message).
inline constexpr const char* kAddressSpaceLimitUnderAsan =
    "AddressSanitizer reserves terabytes of address space for its shadow memory, so an "
    "address-space limit (RLIMIT_AS) cannot be tested in this build";

}  // namespace kinray::test
