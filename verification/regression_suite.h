#pragma once
// The image regression suite (docs/verification.md, "The regression suite"): a fixed list of
// cases -- every built-in scene and a few real animated models, small, at fixed frame times --
// rendered by the kinetic backend with its audit on. Each frame is compared
//  (a) with the reference stored in images/regression/<case>/: the ID buffer exactly, ties aside
//      (FrameComparator), and the shaded image by PSNR and maximum error (ColorThresholds);
//  (b) with the Embree backend rendered now: zero real mismatches.
// A failing case writes heat maps and the offending frames into a report folder. References are
// only ever written by an explicit update (`kinray regress --update-references`), and only for
// frames that agree with Embree, so a reference never records a kinetic bug.
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "verification/image_diff.h"

namespace kinray {

/// Where a case's model file is found.
enum class ModelRoot {
  kNone,        ///< a built-in scene: `scene` is its spec
  kTestModels,  ///< Debian's assimp-testmodels (RegressionConfig::test_models)
  kShared,      ///< the shared folder's models (RegressionConfig::shared_models)
};

/// One case: a scene rendered at fixed frame times.
struct RegressionCase {
  std::string name;   ///< its folder under the references, and its --case name
  std::string scene;  ///< a built-in spec, or a model path relative to `root`
  ModelRoot root = ModelRoot::kNone;
  std::string animation;  ///< model files: which animation (empty: the first)
  int width = 96, height = 72;
  int frames = 4;  ///< evenly over the shot (or `time`), both ends included
  std::optional<std::pair<double, double>> time;  ///< restricts the shot, as --time A:B
};

/// The cases of the suite, in the order they run.
[[nodiscard]] const std::vector<RegressionCase>& regression_cases();
/// The case called `name`; throws InputError naming --case and listing the cases otherwise.
[[nodiscard]] const RegressionCase& find_regression_case(const std::string& name);

/// Thresholds of the shaded-image comparison with a reference, in 8-bit sRGB codes (the stored
/// format); justified in regression_suite.cpp and docs/verification.md.
struct ColorThresholds {
  /// Largest channel difference allowed on pixels whose triangle (or background) agrees.
  int max_code_error = 1;
  /// Smallest PSNR over the whole frame (peak 255), ties included.
  double min_psnr_db = 30;
};

struct RegressionConfig {
  std::string references = "images/regression";  ///< one folder per case
  std::string report;  ///< folder for the diff images of failing cases; empty: none written
  std::string test_models = "/usr/share/assimp/models";
  std::string shared_models = "../shared/data/models";
  bool update = false;  ///< rewrite the references (frames that agree with Embree only)
  bool audit = true;    ///< kinetic backend audit (a violation fails the case)
  int threads = 0;      ///< 0: all cores
  ColorThresholds color;
  TieTolerance tolerance;
};

/// How one frame of a case compared.
struct RegressionFrameResult {
  size_t frame = 0;  ///< index in the case's frame times
  double time = 0;
  size_t covered = 0;  ///< pixels where the kinetic frame shows a triangle
  /// ID buffer against the stored reference (zero when updating).
  size_t reference_real = 0, reference_ties = 0;
  /// Shaded image against the stored reference: PSNR in dB (nullopt: identical) and the largest
  /// channel difference in codes on pixels whose IDs agree.
  std::optional<double> psnr_db;
  int max_code_error = 0;
  /// ID buffer against the Embree backend rendered now.
  size_t embree_real = 0, embree_ties = 0;
  std::vector<std::string> problems;  ///< why the frame fails; empty: it passes
  [[nodiscard]] bool passed() const { return problems.empty(); }
};

enum class RegressionStatus { kPassed, kFailed, kUpdated, kSkipped };
[[nodiscard]] const char* status_name(RegressionStatus status);

/// The outcome of one case.
struct RegressionCaseResult {
  std::string name;
  RegressionStatus status = RegressionStatus::kFailed;
  /// Failed: every problem, one per line, and where the report went; skipped: why.
  std::string message;
  std::string report_folder;  ///< where diff images were written, empty if none
  std::vector<RegressionFrameResult> frames;
  double seconds = 0;  ///< wall time of the case
};

/// Renders `c` with the kinetic backend (audit as configured) and with Embree, compares every
/// frame with the stored reference (or, with config.update, writes the references), and writes
/// the report of a failing case. A case whose model file is not installed is skipped. Never
/// throws for a failing case: load errors, audit violations and missing references are failures
/// with a message.
[[nodiscard]] RegressionCaseResult run_regression_case(const RegressionCase& c, const RegressionConfig& config);

/// One line per case, for `kinray regress`: name, status, frames, worst figures, time.
void print_regression_header(std::ostream& out);
void print_regression_line(std::ostream& out, const RegressionCaseResult& result);

}  // namespace kinray
