#pragma once
// `kinray bench --suite`: the benchmark suite. The built-in scenes and BART's kitchen and robots
// (Lext, Assarsson and Moller 2001), side by side in one process, one row each: events per
// keyframe interval, the break-even in-between count, the speedup against the best Embree mode
// at a few in-between counts (verification/benchmark.h measures each, checking the frames against
// Embree while it measures), and BART's own measure: the time to render the whole animation at
// its frame count, kinetic and best Embree.
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "verification/benchmark.h"

namespace kinray {

/// One scene of the suite: the short name of its row and the scene spec it loads.
struct SuiteScene {
  std::string name;  ///< "wavy-sphere", "kitchen", ...
  std::string spec;  ///< a built-in name or BART's .aff file
};

/// The suite's scenes by name: built-in names and BART's "kitchen" and "robots", whose files are
/// looked for in `bart_folder` (kitchen/kitchen.aff, robots/Robot.aff). Empty `names`: every
/// built-in scene, then kitchen and robots. Throws InputError naming --scenes for an unknown or
/// repeated name and --bart for a BART file that does not exist.
[[nodiscard]] std::vector<SuiteScene> suite_scenes(const std::vector<std::string>& names,
                                                   const std::string& bart_folder);

struct SuiteParams {
  std::vector<SuiteScene> scenes;
  /// Size, threads, sort, keyrate (BART files only), in-between counts, Embree peers,
  /// repetitions and reference frames; bench.base.scene is not read.
  BenchParams bench;
  int intervals = 3;             ///< keyframe intervals measured per scene, from the middle key
  bool whole_animation = false;  ///< BART's measure: the whole animation, kinetic and best Embree
};

/// BART's measure: every frame of the scene's own schedule (BART: its `a` frame count; built-in
/// scenes: 24 frames), rendered once by each side, backend creation and initialisation included.
struct WholeAnimation {
  size_t frames = 0;
  double kinetic_s = 0;
  std::string embree_mode;  ///< the fastest Embree mode at the first in-between count
  double embree_s = 0;
  size_t frames_compared = 0, mismatch_real = 0, mismatch_tie = 0;
};

/// One row of the suite table.
struct SuiteRow {
  SuiteScene scene;
  size_t triangles = 0;
  std::pair<double, double> window;  ///< the time window of the in-between points
  BenchReport report;                ///< one point per in-between count (sweep "inbetweens")
  std::optional<WholeAnimation> whole;
  [[nodiscard]] size_t mismatch_real() const;
};

struct SuiteReport {
  std::vector<SuiteRow> rows;
  int width = 0, height = 0, threads = 0, intervals = 0, repetitions = 0;
  [[nodiscard]] size_t mismatch_real() const;
  /// {"size", "threads", "intervals", "repetitions", "rows": [...]}: the value of "suite".
  [[nodiscard]] nlohmann::json to_json() const;
  /// The suite table.
  void print(std::ostream& out) const;
};

/// The keyframe intervals the suite measures: `intervals` of them from the middle key of
/// `key_times` (fewer when the shot has fewer), as a --time window.
[[nodiscard]] std::pair<double, double> suite_window(const std::vector<double>& key_times,
                                                     int intervals);

/// Runs the suite, one scene loaded at a time; `progress` gets a line before each measurement.
[[nodiscard]] SuiteReport run_suite(const SuiteParams& params,
                                    const std::function<void(const std::string&)>& progress = {});

}  // namespace kinray
