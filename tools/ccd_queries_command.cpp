// kinray ccd-queries FILE.csv: runs a query set of the CCD benchmark of Wang et al. (2021) (the
// format of ../shared/data/ccd/README.md: 8 rows of rational coordinates per query, with the
// exact ground truth) through kinray's primitive CCD and counts true and false positives and
// negatives. Coordinates that are doubles take the same path as meshes (filters, then exact);
// any other rational goes straight to the exact test.
#include <gmpxx.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "kinetic/collision/ccd_query_file.h"
#include "kinetic/collision/exact_ccd.h"
#include "kinetic/collision/primitive_ccd.h"
#include "renderer/output/image_io.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/json_output.h"
#include "util/input_error.h"

namespace kinray {
namespace {

struct CcdQueriesOptions {
  std::string file, type, json;
};

ContactType query_type(const CcdQueriesOptions& options) {
  if (options.type == "vf") return ContactType::vertex_face;
  if (options.type == "ee") return ContactType::edge_edge;
  if (!options.type.empty())
    throw InputError("--type", "expected vf or ee, got '" + options.type + "'");
  const bool vf = options.file.find("vertex-face") != std::string::npos;
  const bool ee = options.file.find("edge-edge") != std::string::npos;
  if (vf == ee)
    throw InputError("--type", "cannot tell vf from ee by the path '" + options.file +
                                   "' (it names neither vertex-face nor edge-edge); give --type");
  return vf ? ContactType::vertex_face : ContactType::edge_edge;
}

void run_ccd_queries(const CcdQueriesOptions& options) {
  // The file first: a missing file is the problem to name, not the --type its path would tell.
  const std::vector<CcdQuery> queries = read_ccd_queries(options.file);
  const ContactType type = query_type(options);
  prepare_json_output(options.json);
  std::uint64_t tp = 0, fp = 0, fn = 0, tn = 0;
  PrimitiveCcdCounters counters;
  const auto begin = std::chrono::steady_clock::now();
  for (const CcdQuery& query : queries) {
    const std::optional<PrimitiveMotion> doubles = exactly_as_doubles(query.motion);
    const bool hit = doubles ? !contact_times(type, *doubles, &counters).empty()
                             : !exact_contact_times(type, query.motion).empty();
    tp += hit && query.truth;
    fp += hit && !query.truth;
    fn += !hit && query.truth;
    tn += !hit && !query.truth;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count();
  const double us_per_query = 1e6 * seconds / double(queries.size());
  std::printf(
      "%s (%s): %zu queries, %llu true positives, %llu false positives, %llu false "
      "negatives, %llu true negatives, %.2f us per query (%llu decided exactly)\n",
      options.file.c_str(), contact_type_name(type), queries.size(), (unsigned long long)tp,
      (unsigned long long)fp, (unsigned long long)fn, (unsigned long long)tn, us_per_query,
      (unsigned long long)counters.exact_decisions);
  if (options.json.empty()) return;
  const nlohmann::json report = {{"file", options.file},
                                 {"type", contact_type_name(type)},
                                 {"queries", queries.size()},
                                 {"true_positives", tp},
                                 {"false_positives", fp},
                                 {"false_negatives", fn},
                                 {"true_negatives", tn},
                                 {"us_per_query", us_per_query},
                                 {"exact_decisions", counters.exact_decisions}};
  write_file_atomically(options.json, report.dump(2) + "\n");
}

}  // namespace

void register_ccd_queries_command(CLI::App& app) {
  auto options = std::make_shared<CcdQueriesOptions>();
  CLI::App* command = app.add_subcommand(
      "ccd-queries",
      "Run a CCD query set (rational CSV with ground truth) through the exact primitive CCD");
  command->add_option("FILE", options->file, "Query file (8 rows per query)")->required();
  command->add_option("--type", options->type,
                      "vf or ee (default: from a path naming vertex-face or edge-edge)");
  command->add_option("--json", options->json, "Write the counts as JSON to FILE");
  command->callback([options] { run_ccd_queries(*options); });
}

}  // namespace kinray
