// kinray bench --suite: every suite scene measured in one process, one table.
#include "tools/bench_suite_command.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// The flags of `kinray bench` that the suite reads; any other one given is refused.
constexpr std::array<const char*, 16> kSuiteFlags = {
    "--suite",       "--scenes",           "--bart", "--intervals",  "--whole-animation",
    "--size",        "--threads",          "--sort", "--inbetweens", "--embree-modes",
    "--repetitions", "--reference-frames", "--json", "--quiet",      "--keyrate",
    "--help"};
constexpr std::array<const char*, 4> kSuiteOnly = {"--scenes", "--bart", "--intervals",
                                                   "--whole-animation"};

bool listed(std::span<const char* const> names, const std::string& name) {
  return std::any_of(names.begin(), names.end(), [&](const char* n) { return name == n; });
}

}  // namespace

void add_suite_options(CLI::App& command, SuiteOptions& options) {
  const char* group = "Suite";
  command
      .add_flag("--suite", options.enabled,
                "Run the benchmark suite (the built-in scenes and BART's kitchen and robots) "
                "instead of SCENE: "
                "one table; size 320x240 and in-betweens 1,16,128 unless given")
      ->group(group);
  command
      .add_option("--scenes", options.scenes,
                  "Suite: only these scenes, a list (built-in names, kitchen, robots)")
      ->group(group);
  command
      .add_option("--bart", options.bart, "Suite: the folder of BART's scenes (kitchen/, robots/)")
      ->capture_default_str()
      ->group(group);
  command
      .add_option("--intervals", options.intervals,
                  "Suite: keyframe intervals measured per scene, from the middle key of its shot")
      ->capture_default_str()
      ->group(group);
  command
      .add_flag("--whole-animation", options.whole_animation,
                "Suite: add BART's measure, every frame of each animation at its frame count "
                "(BART: 800), "
                "kinetic and the best Embree mode (long)")
      ->group(group);
}

void check_suite_flags(const CLI::App& command, const SuiteOptions& options) {
  for (const CLI::Option* option : command.get_options()) {
    if (option->count() == 0) continue;
    const std::string name = option->get_name();
    if (options.enabled && !listed(kSuiteFlags, name))
      throw InputError(name, "does not combine with --suite");
    if (!options.enabled && listed(kSuiteOnly, name))
      throw InputError(name, "applies to --suite only");
  }
}

std::vector<SuiteScene> resolve_suite_scenes(const SuiteOptions& options) {
  std::vector<std::string> names;
  std::stringstream in(options.scenes);
  for (std::string item; std::getline(in, item, ',');) {
    if (item.empty())
      throw InputError("--scenes",
                       "expected a comma-separated list of names, got '" + options.scenes + "'");
    names.push_back(item);
  }
  if (!options.scenes.empty() && names.empty()) throw InputError("--scenes", "the list is empty");
  if (options.intervals < 1 || options.intervals > 1000)
    throw InputError("--intervals",
                     "must lie in 1..1000, got " + std::to_string(options.intervals));
  return suite_scenes(names, options.bart);
}

void run_suite_command(const SuiteOptions& options, std::vector<SuiteScene> scenes,
                       const BenchParams& bench, const std::string& json, bool quiet) {
  if (bench.base.keyrate != 0 && std::none_of(scenes.begin(), scenes.end(),
                                              [](const SuiteScene& s) { return s.name != s.spec; }))
    throw InputError("--keyrate", "applies to BART's scenes, and none is in --scenes");
  if (!json.empty()) check_output_file(json, "--json");
  SuiteParams params;
  params.scenes = std::move(scenes);
  params.bench = bench;
  params.intervals = options.intervals;
  params.whole_animation = options.whole_animation;
  const SuiteReport report = run_suite(params, [&](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "%s\n", line.c_str());
  });
  report.print(std::cout);
  if (!json.empty())
    write_file_atomically(json, nlohmann::json{{"suite", report.to_json()}}.dump(2) + "\n");
  if (const size_t real = report.mismatch_real(); real > 0)
    throw std::runtime_error("the kinetic frames disagree with Embree on " + std::to_string(real) +
                             " pixels beyond ties: the suite's figures are not valid");
}

}  // namespace kinray
