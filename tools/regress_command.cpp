// kinray regress [--update-references] [--report DIR] [--case NAME]...: the image regression suite
// (verification/regression_suite.h). Renders every case with the kinetic backend (audit on) and
// with Embree, compares each frame with the stored references and with Embree, prints one line per
// case, writes heat maps and frames of failing cases into the report folder, and exits 0 only when
// every case passed (or was updated, or skipped because its model is not installed). References
// are rewritten only with --update-references, and only for cases that agree with Embree.
#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "renderer/output/output_check.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "util/input_error.h"
#include "verification/regression_suite.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

struct RegressOptions {
  RegressionConfig config;
  std::vector<std::string> cases;
  std::string shared = "../shared";
  bool no_audit = false;
  bool quiet = false;
};

void run_regress(RegressOptions options) {
  RegressionConfig config = options.config;
  config.shared_models = (fs::path(options.shared) / "data" / "models").string();
  config.audit = !options.no_audit;
  if (config.threads < 0) throw InputError("--threads", "must be >= 0, got " + std::to_string(config.threads));
  std::vector<const RegressionCase*> cases;
  for (const std::string& name : options.cases) cases.push_back(&find_regression_case(name));
  if (cases.empty())
    for (const RegressionCase& c : regression_cases()) cases.push_back(&c);
  std::error_code error;
  if (!config.update && !fs::is_directory(config.references, error))
    throw InputError("--references", "'" + config.references +
                                         "' is not a folder (run from the repository root, or give --references DIR)");
  if (!config.report.empty()) check_output_folder(config.report, "--report");
  if (config.update) check_output_folder(config.references, "--references");

  if (!options.quiet) {
    std::cout << "regression suite: kinetic backend" << (config.audit ? " (audit on)" : "")
              << " against the references in " << config.references << " and against embree\n";
    print_regression_header(std::cout);
  }
  size_t failed = 0, passed = 0, updated = 0, skipped = 0;
  for (const RegressionCase* c : cases) {
    const RegressionCaseResult result = run_regression_case(*c, config);
    switch (result.status) {
      case RegressionStatus::kPassed: ++passed; break;
      case RegressionStatus::kFailed: ++failed; break;
      case RegressionStatus::kUpdated: ++updated; break;
      case RegressionStatus::kSkipped: ++skipped; break;
    }
    if (!options.quiet || result.status == RegressionStatus::kFailed) {
      print_regression_line(options.quiet ? std::cerr : std::cout, result);
      (options.quiet ? std::cerr : std::cout).flush();
    }
  }
  if (!options.quiet)
    std::cout << "total: " << cases.size() << " cases, " << passed << " passed, " << updated << " updated, " << skipped
              << " skipped, " << failed << " failed" << (failed && !config.report.empty() ? "; report in " + config.report : "")
              << "\n";
  if (failed > 0)
    throw std::runtime_error("regress: " + std::to_string(failed) + " of " + std::to_string(cases.size()) +
                             " cases failed");
}

}  // namespace

void register_regress_command(CLI::App& app) {
  CLI::App* command = app.add_subcommand(
      "regress", "Run the image regression suite: every case rendered by the kinetic backend (audit on), compared "
                 "with its stored references and with Embree");
  auto options = std::make_shared<RegressOptions>();
  options->config.report = "out/regression";
  command->add_flag("--update-references", options->config.update,
                    "Rewrite the stored references from this build (only cases whose frames agree with Embree)");
  command->add_option("--case", options->cases, "Run only this case (repeatable); default: every case");
  command->add_option("--references", options->config.references, "Folder of the stored references")
      ->capture_default_str();
  command->add_option("--report", options->config.report,
                      "Folder for the heat maps and frames of failing cases (DIR/<case>/); \"\" for none")
      ->capture_default_str();
  command->add_option("--shared", options->shared, "The shared folder (models under data/models)")
      ->capture_default_str();
  command->add_option("--test-models", options->config.test_models, "Debian's assimp-testmodels folder")
      ->capture_default_str();
  add_threads_option(*command, options->config.threads, "Render threads (0: all cores)");
  command->add_flag("--no-audit", options->no_audit, "Do not audit the kinetic backend (faster)");
  command->add_flag("-q,--quiet", options->quiet, "Print failing cases only");
  command->callback([options] { run_regress(*options); });
}

}  // namespace kinray
