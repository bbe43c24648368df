// kinray ccd-queries FILE.csv|FOLDER...: runs query sets of the CCD benchmark of Wang et al.
// (2021) (the format of ../shared/data/ccd/README.md: 8 rows of rational coordinates per query,
// with the exact ground truth) through kinray's primitive CCD, and prints one row per set: its
// queries, the time per query, and the false positives and negatives. Coordinates that are
// doubles take the same path as meshes (filters, then exact), through the batch API a simulator
// calls; any other rational goes straight to the exact test. The timed loop holds the tests
// alone: reading, converting the coordinates to doubles and checking that they are exact happen
// once per file, before it.
#include <gmpxx.h>

#include <algorithm>
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

namespace fs = std::filesystem;

struct CcdQueriesOptions {
  std::vector<std::string> paths;
  std::string type, json;
  int threads = 1;
  int repetitions = 3;
  bool stats = false;
};

ContactType query_type(const CcdQueriesOptions& options, const std::string& file) {
  if (options.type == "vf") return ContactType::vertex_face;
  if (options.type == "ee") return ContactType::edge_edge;
  if (!options.type.empty())
    throw InputError("--type", "expected vf or ee, got '" + options.type + "'");
  const bool vf = file.find("vertex-face") != std::string::npos;
  const bool ee = file.find("edge-edge") != std::string::npos;
  if (vf == ee)
    throw InputError("--type", "cannot tell vf from ee by the path '" + file +
                                   "' (it names neither vertex-face nor edge-edge); give --type");
  return vf ? ContactType::vertex_face : ContactType::edge_edge;
}

/// The files named: a folder stands for every .csv below it, in path order.
std::vector<std::string> query_files(const std::vector<std::string>& paths) {
  std::vector<std::string> files;
  for (const std::string& path : paths) {
    std::error_code error;
    if (!fs::is_directory(path, error)) {
      files.push_back(path);
      continue;
    }
    std::vector<std::string> found;
    for (const auto& entry : fs::recursive_directory_iterator(path))
      if (entry.is_regular_file() && entry.path().extension() == ".csv")
        found.push_back(entry.path().string());
    if (found.empty()) throw InputError(path, "no .csv query files in the folder");
    std::ranges::sort(found);
    files.insert(files.end(), found.begin(), found.end());
  }
  return files;
}

/// The benchmark's name of a set: "erleben-wedges data_0_1" for
/// .../erleben-wedges/edge-edge/data_0_1.csv, else the path.
std::string set_name(const std::string& file) {
  const fs::path path(file);
  const std::string kind = path.parent_path().filename().string();
  if (kind != "vertex-face" && kind != "edge-edge") return file;
  return path.parent_path().parent_path().filename().string() + " " + path.stem().string();
}

struct SetResult {
  std::string file, set;
  ContactType type = ContactType::vertex_face;
  std::uint64_t queries = 0, tp = 0, fp = 0, fn = 0, tn = 0;
  double us_per_query = 0;
  PrimitiveCcdCounters counters;
  std::uint64_t rational_only = 0;  ///< queries whose coordinates are not all doubles
};

SetResult run_set(const CcdQueriesOptions& options, const std::string& file) {
  // The file first: a missing file is the problem to name, not the --type its path would tell.
  const std::vector<CcdQuery> queries = read_ccd_queries(file);
  SetResult result;
  result.file = file;
  result.set = set_name(file);
  result.type = query_type(options, file);
  result.queries = queries.size();
  std::vector<PrimitiveQuery> doubles;
  std::vector<size_t> double_index, rational_index;
  for (size_t i = 0; i < queries.size(); ++i) {
    if (queries[i].doubles) {
      doubles.push_back({result.type, *queries[i].doubles});
      double_index.push_back(i);
    } else {
      rational_index.push_back(i);
    }
  }
  result.rational_only = rational_index.size();
  std::vector<bool> hit(queries.size());
  std::vector<double> seconds;
  for (int repetition = 0; repetition < std::max(1, options.repetitions); ++repetition) {
    // counters from the first run only: every run decides the same way
    PrimitiveCcdCounters* counters = repetition == 0 ? &result.counters : nullptr;
    const auto begin = std::chrono::steady_clock::now();
    const std::vector<std::optional<double>> first =
        first_contact_times(doubles, counters, {.threads = options.threads});
    std::vector<bool> exact_hit(rational_index.size());
    for (size_t k = 0; k < rational_index.size(); ++k)
      exact_hit[k] = !exact_contact_times(result.type, queries[rational_index[k]].motion).empty();
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - begin).count());
    for (size_t k = 0; k < double_index.size(); ++k) hit[double_index[k]] = first[k].has_value();
    for (size_t k = 0; k < rational_index.size(); ++k) hit[rational_index[k]] = exact_hit[k];
  }
  std::ranges::sort(seconds);
  result.us_per_query = 1e6 * seconds[seconds.size() / 2] / double(queries.size());
  for (size_t i = 0; i < queries.size(); ++i) {
    const bool truth = queries[i].truth;
    result.tp += hit[i] && truth;
    result.fp += hit[i] && !truth;
    result.fn += !hit[i] && truth;
    result.tn += !hit[i] && !truth;
  }
  return result;
}

nlohmann::json counters_json(const PrimitiveCcdCounters& counters) {
  nlohmann::json out = nlohmann::json::object();
  counters.for_each_counter([&](const char* key, std::uint64_t value) { out[key] = value; });
  return out;
}

void run_ccd_queries(const CcdQueriesOptions& options) {
  if (options.repetitions < 1)
    throw InputError("--repetitions",
                     "expected at least 1, got " + std::to_string(options.repetitions));
  if (options.threads < 0)
    throw InputError("--threads",
                     "expected 0 (all cores) or more, got " + std::to_string(options.threads));
  const std::vector<std::string> files = query_files(options.paths);
  prepare_json_output(options.json);
  std::vector<SetResult> results;
  for (const std::string& file : files) results.push_back(run_set(options, file));
  SetResult total;
  total.set = "all";
  double total_us = 0;
  std::printf(
      "| set | type | queries | us per query | false positives | false negatives | decided "
      "in rationals |\n|---|---|---|---|---|---|---|\n");
  for (const SetResult& r : results) {
    std::printf("| %s | %s | %llu | %.2f | %llu | %llu | %llu |\n", r.set.c_str(),
                contact_type_name(r.type), (unsigned long long)r.queries, r.us_per_query,
                (unsigned long long)r.fp, (unsigned long long)r.fn,
                (unsigned long long)(r.counters.exact_decisions + r.rational_only));
    total.queries += r.queries;
    total.tp += r.tp;
    total.fp += r.fp;
    total.fn += r.fn;
    total.tn += r.tn;
    total.counters += r.counters;
    total.rational_only += r.rational_only;
    total_us += r.us_per_query * double(r.queries);
  }
  total.us_per_query = total_us / double(std::max<std::uint64_t>(1, total.queries));
  if (results.size() > 1)
    std::printf("| all | | %llu | %.2f | %llu | %llu | %llu |\n", (unsigned long long)total.queries,
                total.us_per_query, (unsigned long long)total.fp, (unsigned long long)total.fn,
                (unsigned long long)(total.counters.exact_decisions + total.rational_only));
  std::printf(
      "%llu true positives, %llu true negatives; us per query: median of %d runs, %d "
      "thread%s\n",
      (unsigned long long)total.tp, (unsigned long long)total.tn, options.repetitions,
      options.threads, options.threads == 1 ? "" : "s");
  if (options.stats) {
    for (const SetResult& r : results) {
      std::printf("%s (%s):", r.set.c_str(), contact_type_name(r.type));
      r.counters.for_each_counter([](const char* key, std::uint64_t value) {
        std::printf(" %s %llu", key, (unsigned long long)value);
      });
      std::printf("\n");
    }
  }
  if (options.json.empty()) return;
  const auto set_json = [](const SetResult& r) {
    return nlohmann::json{{"file", r.file},
                          {"set", r.set},
                          {"type", contact_type_name(r.type)},
                          {"queries", r.queries},
                          {"true_positives", r.tp},
                          {"false_positives", r.fp},
                          {"false_negatives", r.fn},
                          {"true_negatives", r.tn},
                          {"us_per_query", r.us_per_query},
                          {"exact_decisions", r.counters.exact_decisions},
                          {"rational_queries", r.rational_only},
                          {"stats", counters_json(r.counters)}};
  };
  // the totals at the top level, the sets' rows under "sets"
  nlohmann::json report = set_json(total);
  report.erase("file");
  report.erase("type");
  report["threads"] = options.threads;
  report["repetitions"] = options.repetitions;
  report["sets"] = nlohmann::json::array();
  for (const SetResult& r : results) report["sets"].push_back(set_json(r));
  write_file_atomically(options.json, report.dump(2) + "\n");
}

}  // namespace

void register_ccd_queries_command(CLI::App& app) {
  auto options = std::make_shared<CcdQueriesOptions>();
  CLI::App* command = app.add_subcommand(
      "ccd-queries",
      "Run CCD query sets (rational CSV with ground truth) through the exact primitive CCD, one "
      "table row per set");
  command
      ->add_option("FILE", options->paths,
                   "Query files (8 rows per query), or folders of them (every .csv below)")
      ->required();
  command->add_option("--type", options->type,
                      "vf or ee (default: from a path naming vertex-face or edge-edge)");
  add_threads_option(*command, options->threads, "Threads of the batch of tests (0: all cores)");
  command
      ->add_option("--repetitions", options->repetitions,
                   "Timed runs of each set; the median is reported")
      ->capture_default_str();
  command->add_flag("--stats", options->stats, "Print how each set's tests were decided");
  command->add_option("--json", options->json, "Write the counts as JSON to FILE");
  command->callback([options] { run_ccd_queries(*options); });
}

}  // namespace kinray
