#pragma once
// CLI11's parse errors in kinray's words: one place that turns "Could not convert: --frames =
// many" or "The following argument was not expected: --camera" into an InputError naming the flag,
// so every subcommand and every flag, present or future, gets the same one-line errors.
#include <CLI/CLI.hpp>

#include "util/input_error.h"

namespace kinray {

/// The InputError that says what `error` means on the command line of `app` (the top-level app;
/// the subcommand that was being parsed is found from it).
[[nodiscard]] InputError explain_parse_error(const CLI::App& app, const CLI::ParseError& error);

/// The library names a bad option by its config field (OptionError: "embree_packet"); the user
/// gave a flag (--packet). The same error, naming the flag.
[[nodiscard]] InputError name_the_flag(const OptionError& error);

}  // namespace kinray
