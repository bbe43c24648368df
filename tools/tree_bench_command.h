#pragma once
// `kinray bench SCENE --structure aabb,boxtree`: the kinetic trees' benchmark
// (verification/tree_benchmark.h), reached from tools/bench_command.cpp.
#include <string>

#include "renderer/job/render_job.h"

namespace kinray {

/// Runs the trees' benchmark; throws InputError naming the flag at fault before measuring.
void run_tree_bench(const RenderParams& base, const std::string& structure,
                    const std::string& inbetweens, const std::string& triangles, int repetitions,
                    const std::string& json, const std::string& charts, bool quiet);

}  // namespace kinray
