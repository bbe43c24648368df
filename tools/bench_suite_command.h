#pragma once
// `kinray bench --suite`: the benchmark suite (verification/bench_suite.h), reached from
// tools/bench_command.cpp, which resolves the flags it shares with `bench SCENE`.
#include <CLI/CLI.hpp>
#include <string>

#include "verification/bench_suite.h"

namespace kinray {

/// The flags only the suite reads.
struct SuiteOptions {
  bool enabled = false;                      ///< --suite
  std::string scenes;                        ///< --scenes: names, comma-separated; empty: all
  std::string bart = "../shared/data/bart";  ///< --bart: the folder of BART's scenes
  int intervals = 3;                         ///< --intervals
  bool whole_animation = false;              ///< --whole-animation: add BART's measure
};

/// The suite's defaults where `bench SCENE` has others.
inline constexpr const char* kSuiteSize = "320x240";
inline constexpr const char* kSuiteInbetweens = "1,16,128";

/// --suite, --scenes, --bart, --intervals, --whole-animation.
void add_suite_options(CLI::App& command, SuiteOptions& options);

/// Throws InputError naming the first flag given to `command` that the suite does not read (the
/// SCENE, the sweeps, --time, --csv, --charts, --structure, the motion blur flags...), or a suite
/// flag given without --suite.
void check_suite_flags(const CLI::App& command, const SuiteOptions& options);

/// The scenes of --scenes and --bart. Throws InputError naming the flag at fault.
[[nodiscard]] std::vector<SuiteScene> resolve_suite_scenes(const SuiteOptions& options);

/// Runs the suite with `bench`'s size, threads and peers, prints the table and writes
/// {"suite": ...} to `json` (if not empty); fails (exit 1) on real mismatches.
void run_suite_command(const SuiteOptions& options, std::vector<SuiteScene> scenes,
                       const BenchParams& bench, const std::string& json, bool quiet);

}  // namespace kinray
