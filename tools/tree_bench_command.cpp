#include "tools/tree_bench_command.h"

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "renderer/output/image_io.h"
#include "util/input_error.h"
#include "verification/benchmark.h"
#include "verification/tree_benchmark.h"

namespace kinray {

void run_tree_bench(const RenderParams& base, const std::string& structure,
                    const std::string& inbetweens, const std::string& triangles, int repetitions,
                    const std::string& json, const std::string& charts, bool quiet) {
  TreeBenchParams params;
  params.base = base;
  params.structures = parse_tree_structures(structure);
  params.inbetweens = parse_int_list(inbetweens, "--inbetweens");
  if (!triangles.empty()) params.triangles = parse_int_list(triangles, "--triangles");
  if (repetitions < 1) throw InputError("--repetitions", "must be at least 1");
  params.repetitions = repetitions;
  if (!json.empty() && std::filesystem::is_directory(json)) throw InputError(json, "is a folder");
  const TreeBenchReport report = run_tree_benchmark(params, [&](const std::string& line) {
    if (!quiet) std::fprintf(stderr, "%s\n", line.c_str());
  });
  report.print(std::cout);
  if (!json.empty()) write_file_atomically(json, report.to_json().dump(2) + "\n");
  if (!charts.empty())
    for (const std::string& path : report.write_charts(charts))
      std::printf("chart: %s\n", path.c_str());
}

}  // namespace kinray
