#pragma once
// `kinray bench SCENE --structure ksl,swept`: the kinetic separation list against swept volumes
// (and brute force, when listed) in one process, in the shape of Zachmann and Weller's tables:
// time per collision check against interpolated frames (checks per keyframe interval) and against
// the triangle count. Reached from tools/bench_command.cpp.
#include <string>

namespace kinray {

/// Runs the sweeps; throws InputError naming the flag at fault before measuring, and
/// std::runtime_error when two structures report different contact sets. With `charts`, writes
/// per sweep a PNG of the time per check and one of the speedup against swept volumes there.
void run_collide_bench(const std::string& scene, const std::string& structures,
                       const std::string& inbetweens, const std::string& triangles, int repetitions,
                       const std::string& json, const std::string& charts, bool quiet);

}  // namespace kinray
