#pragma once
// Fuzz targets: one entry point per parser of untrusted input, run by the libFuzzer harnesses
// (KINRAY_FUZZ build, tests/fuzz/CMakeLists.txt) and by the normal test suite, which replays
// every seed and every saved crash input through the same entry point (test_fuzz_replay.cpp).
//
// A target feeds the bytes to its parser and accepts exactly one way of refusing them: an
// InputError (the one clear line of the project's rules). Any other exception escapes, and a
// crash, a sanitizer report or a hang is a finding as well.
//
// Adding a target: a file tests/fuzz/targets/NAME.cpp with
//   KINRAY_FUZZ_TARGET(NAME) { parse(bytes); }   // bytes: std::span<const uint8_t>
// a line kinray_fuzz_target(NAME) in tests/fuzz/CMakeLists.txt, and a few small seed inputs in
// tests/fuzz/corpus/NAME/.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace kinray::fuzz {

using Entry = void (*)(std::span<const uint8_t> bytes);

/// A named entry point; registered at start-up by KINRAY_FUZZ_TARGET.
struct Target {
  std::string name;
  Entry entry = nullptr;
};

/// Every target linked into this program, in registration order.
[[nodiscard]] std::vector<Target>& targets();

/// Registers a target (used by KINRAY_FUZZ_TARGET); returns true so it can initialise a static.
bool register_target(std::string name, Entry entry);

/// Runs `entry` on `bytes`: an InputError is the accepted refusal and is swallowed; anything
/// else propagates.
void run_target(Entry entry, std::span<const uint8_t> bytes);

/// A private scratch folder for targets whose parser reads a file (created on first use, one per
/// process, removed at exit).
[[nodiscard]] const std::string& scratch_folder();

/// Writes `bytes` to scratch_folder()/`name` and returns the path.
[[nodiscard]] std::string write_scratch_file(std::string_view name, std::span<const uint8_t> bytes);

}  // namespace kinray::fuzz

#define KINRAY_FUZZ_TARGET(name)                                     \
  static void kinray_fuzz_##name(std::span<const uint8_t> bytes);    \
  [[maybe_unused]] static const bool kinray_fuzz_registered_##name = \
      ::kinray::fuzz::register_target(#name, &kinray_fuzz_##name);   \
  static void kinray_fuzz_##name(std::span<const uint8_t> bytes)
