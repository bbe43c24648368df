#pragma once
// The --stats of the kinetic trees and of the bottom-up tree as JSON: events by kind and the four
// quality measures of docs/design.md (compactness, responsiveness, locality, efficiency), shared by
// the shadow tracer and the benchmark.
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "renderer/shadows/shadow_tracer.h"

namespace kinray {

class KineticBvh;
class BottomUpBvh;

/// Adds "events" (by kind), "quality", "certificates" and "tree" to `out`.
void write_kinetic_tree_stats(const KineticBvh& tree, nlohmann::json& out);
/// Adds "bv_updates", "updates" and "tree" to `out`.
void write_bottom_up_stats(const BottomUpBvh& tree, nlohmann::json& out);

}  // namespace kinray
