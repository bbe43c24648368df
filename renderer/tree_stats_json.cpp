#include "renderer/tree_stats_json.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "renderer/stats_json.h"
#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/kinetic_bvh.h"

namespace kinray {

void write_kinetic_tree_stats(const KineticBvh& tree, nlohmann::json& out) {
  const TreeStats s = tree.stats();
  out["events"] = event_counts_json(s.events);
  out["events_external"] = s.events_external;
  out["events_internal"] = s.events_internal;
  out["realizer_changes"] = s.realizer_changes;
  out["certificates"] = {{"live", s.certificates_live},
                         {"live_max", s.certificates_live_max},
                         {"computed", s.certificates_computed},
                         {"decided_at_keys", s.certificates_by_keys},
                         {"scheduled", s.scheduled_events}};
  out["quality"] = quality_json({s.certificates_live_max, s.certificates_live,
                                   s.certificates_computed, s.events.total(),
                                   s.events_internal, s.events_external, s.triangles_present});
  out["tree"] = {{"shape", tree.shape() == TreeShape::aabb ? "aabb" : "boxtree"},
                 {"nodes", s.nodes},
                 {"height", s.height},
                 {"node_sides", s.node_sides},
                 {"triangles", s.triangles},
                 {"triangles_present", s.triangles_present},
                 {"memory_bytes", tree.memory_bytes()}};
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
