#include "renderer/output/tree_stats_json.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "renderer/output/stats_json.h"
#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"

namespace kinray {

void write_kinetic_tree_stats(const KineticBvh& tree, nlohmann::json& out) {
  const TreeStats s = tree.stats();
  out["events"] = event_counts_json(s.events);
  out.update(counters_json(s));
  out["certificates"] = section_json([&](auto visit) { s.for_each_certificate_counter(visit); });
  out["quality"] = quality_json({s.certificates_live_max, s.certificates_live,
                                   s.certificates_computed, s.events.total(),
                                   s.events_internal, s.events_external, s.triangles_present});
  out["tree"] = section_json([&](auto visit) { s.for_each_shape_counter(visit); });
  out["tree"]["shape"] = tree.shape() == TreeShape::aabb ? "aabb" : "boxtree";
  out["tree"]["memory_bytes"] = tree.memory_bytes();
}

void write_bottom_up_stats(const BottomUpBvh& tree, nlohmann::json& out) {
  out["bv_updates"] = tree.box_updates();
  out["updates"] = tree.updates();
  out["tree"] = {{"shape", "aabb"},
                 {"nodes", tree.topology().nodes.size()},
                 {"height", tree.topology().height()},
                 {"triangles", tree.meshes().triangle_count()},
                 {"memory_bytes", tree.memory_bytes()}};
}

}  // namespace kinray
