#pragma once
// `kinray bench SCENE --structure aabb,boxtree`: the kinetic AABB tree and the kinetic BoxTree
// against the bottom-up update of the same tree, Embree refit and Embree rebuild, in one process,
// in the shape of Zachmann and Weller's tables ("#Events and #Updates", "Updating time", "Total
// time"): events per keyframe interval against the bottom-up method's box updates, update time
// per frame, and total time per frame with shadow queries (one point light, shadow rays from
// Embree's primary hits). Every structure answers the same shadow rays; the trees must agree ray
// for ray (they share the triangle test), Embree's float answers are counted against them.
#include <functional>
#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/job/render_job.h"
#include "renderer/shadows/shadow_tracer.h"

namespace kinray {

struct TreeBenchParams {
  RenderParams base;                         ///< scene, --size (shadow rays), --time, model flags
  std::vector<int> inbetweens = {1, 4, 16};  ///< the in-betweens sweep
  std::vector<int> triangles;  ///< the triangles sweep (built-in scenes), at 16 or the last K
  std::vector<ShadowTree> structures = {ShadowTree::aabb, ShadowTree::boxtree};
  int repetitions = 3;    ///< medians over this many runs
  int shadow_frames = 6;  ///< frames whose shadow queries are timed, spread over the shot
};

/// Parses "aabb,boxtree" (also "refit"). Throws InputError naming --structure.
[[nodiscard]] std::vector<ShadowTree> parse_tree_structures(const std::string& text);

/// One structure measured on one configuration.
struct TreeBenchPoint {
  std::string sweep, scene, tree;
  int inbetweens = 0;
  size_t triangles = 0, frames = 0, key_intervals = 0, shadow_rays_per_frame = 0;
  double events_per_interval = 0;        ///< every event of the kinetic tree (all kinds)
  double failures_per_interval = 0;      ///< of which leaf and tree events
  double certificates_per_interval = 0;  ///< certificate computations (key updates included)
  double bv_updates_per_interval = 0;    ///< boxes recomputed by the bottom-up update
  double kinetic_update_ms_per_frame = 0, bottom_up_update_ms_per_frame = 0;
  double embree_refit_update_ms_per_frame = 0, embree_rebuild_update_ms_per_frame = 0;
  double update_speedup = 0;  ///< bottom_up_update_ms_per_frame / kinetic_update_ms_per_frame
  double shadow_ms_per_frame = 0, bottom_up_shadow_ms_per_frame = 0,
         embree_refit_shadow_ms_per_frame = 0, embree_rebuild_shadow_ms_per_frame = 0;
  double total_ms_per_frame = 0;  ///< kinetic update + shadow queries
  double bottom_up_total_ms_per_frame = 0, embree_refit_total_ms_per_frame = 0,
         embree_rebuild_total_ms_per_frame = 0;
  double build_ms = 0;                ///< the static builder and the first certificates (once)
  size_t embree_mask_mismatches = 0;  ///< shadow rays on which Embree (float) answered otherwise
  nlohmann::json stats;               ///< the tree's --stats (events by kind, quality)
};

struct TreeBenchReport {
  std::vector<TreeBenchPoint> points;
  [[nodiscard]] nlohmann::json to_json() const;
  /// PNG charts of the sweeps into `folder`; returns the paths.
  std::vector<std::string> write_charts(const std::string& folder) const;
  void print(std::ostream& out) const;
};

/// Runs every configuration; `progress` gets a line before each one. Throws std::runtime_error
/// when two trees answer a shadow ray differently (a bug, not a tie).
[[nodiscard]] TreeBenchReport run_tree_benchmark(
    const TreeBenchParams& params, const std::function<void(const std::string&)>& progress = {});

}  // namespace kinray
