#include "verification/tree_benchmark.h"

#include <algorithm>
#include <ctime>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "renderer/backends/backend.h"
#include "renderer/frame.h"
#include "renderer/output/tree_stats_json.h"
#include "renderer/shadows/embree_shadow_tracer.h"
#include "renderer/shadows/kinetic_shadow_tracer.h"
#include "renderer/shadows/tree_shadow_tracer.h"
#include "util/input_error.h"
#include "verification/bench_support.h"

namespace kinray {

std::vector<ShadowTree> parse_tree_structures(const std::string& text) {
  std::vector<ShadowTree> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const std::optional<ShadowTree> tree = find_enum(kShadowTreeNames, item);
    if (tree && tree != ShadowTree::brute)
      out.push_back(*tree);
    else
      throw InputError("--structure",
                       "unknown structure '" + item + "' (available: grid, aabb, boxtree, refit)");
  }
  if (out.empty()) throw InputError("--structure", "no structure given");
  return out;
}

namespace {

/// Process CPU time, not wall time: these machines are shared (load far above the core count),
/// and every structure measured here runs on one thread (Embree's device for shadow rays too).
struct Clock {
  using time_point = double;
  static double now() {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
  }
};

double ms_since(double start) {
  return Clock::now() - start;
}

/// Shadow rays towards one point light from the primary hits of a frame (camera space: the hit
/// of pixel (i, j) at depth z is z (x_i, y_j, 1)). The light sits above and to the left of the
/// scene, at the median hit depth.
std::vector<ShadowRay> shadow_rays(const Frame& frame, const PixelRays& image) {
  std::vector<float> depths;
  for (float z : frame.depth)
    if (std::isfinite(z)) depths.push_back(z);
  if (depths.empty()) return {};
  std::nth_element(depths.begin(), depths.begin() + long(depths.size() / 2), depths.end());
  const double z = depths[depths.size() / 2];
  const Vec3 light(-0.8 * z, 1.5 * z, 0.2 * z);
  std::vector<ShadowRay> rays;
  for (int j = 0; j < frame.height; ++j)
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = size_t(j) * size_t(frame.width) + size_t(i);
      if (frame.object[p] == kNoHit) continue;
      ShadowRay r;
      r.origin = double(frame.depth[p]) * image.direction(i, j);
      r.direction = light - r.origin;
      r.s_max = 1;
      r.object = frame.object[p];
      r.prim = frame.prim[p];
      rays.push_back(r);
    }
  return rays;
}

/// One structure run over every frame: update time per frame (the first frame builds it and is
/// not counted), shadow query time per timed frame, and the masks of those frames.
struct Run {
  double update_ms_per_frame = 0, shadow_ms_per_frame = 0, build_ms = 0;
  std::vector<std::vector<uint8_t>> masks;
  nlohmann::json stats;
};

Run run(ShadowTracer& tracer, const std::vector<double>& times, const std::vector<size_t>& timed,
        const std::vector<std::vector<ShadowRay>>& rays) {
  Run r;
  double update = 0;
  std::vector<double> shadow;
  size_t next = 0;
  for (size_t f = 0; f < times.size(); ++f) {
    auto start = Clock::now();
    tracer.advance_to(times[f]);
    (f == 0 ? r.build_ms : update) += ms_since(start);
    if (next < timed.size() && timed[next] == f) {
      std::vector<uint8_t> mask(rays[next].size());
      start = Clock::now();
      tracer.occluded(rays[next], mask);
      shadow.push_back(ms_since(start));
      r.masks.push_back(std::move(mask));
      ++next;
    }
  }
  r.update_ms_per_frame = times.size() > 1 ? update / double(times.size() - 1) : 0;
  r.shadow_ms_per_frame = median(shadow);
  tracer.write_stats(r.stats);
  return r;
}

struct Measured {
  std::vector<Run> runs;  ///< per repetition
  [[nodiscard]] double update() const {
    std::vector<double> v;
    for (const Run& r : runs) v.push_back(r.update_ms_per_frame);
    return median(v);
  }
  [[nodiscard]] double shadow() const {
    std::vector<double> v;
    for (const Run& r : runs) v.push_back(r.shadow_ms_per_frame);
    return median(v);
  }
};

/// The bottom-up tree, Embree refit and Embree rebuild on one configuration.
struct Peers {
  Measured bottom_up, refit, rebuild;
};

/// Counts and times of one kinetic tree and its peers into p (key_intervals and tree set);
/// throws when the tree and the bottom-up tree answer a shadow ray differently.
void fill_measurements(TreeBenchPoint& p, const Measured& kinetic, const Peers& peers) {
  const nlohmann::json& s = kinetic.runs.front().stats["shadow_tree"];
  const double n = double(p.key_intervals);
  if (s.contains("events")) {
    p.events_per_interval = s["events"]["total"].get<double>() / n;
    p.failures_per_interval =
        (s["events"]["leaf"].get<double>() + s["events"]["tree"].get<double>()) / n;
    p.certificates_per_interval = s["certificates"]["computed"].get<double>() / n;
  } else {  // refit: the bottom-up tree as the structure under test
    p.events_per_interval = s["bv_updates"].get<double>() / n;
  }
  // The first pass builds the tree (not an update, as the first frame of every structure).
  const nlohmann::json& b = peers.bottom_up.runs.front().stats["shadow_tree"];
  const double passes = b["updates"].get<double>();
  p.bv_updates_per_interval = b["bv_updates"].get<double>() * (passes - 1) / passes / n;
  p.kinetic_update_ms_per_frame = kinetic.update();
  p.bottom_up_update_ms_per_frame = peers.bottom_up.update();
  p.embree_refit_update_ms_per_frame = peers.refit.update();
  p.embree_rebuild_update_ms_per_frame = peers.rebuild.update();
  p.update_speedup = p.kinetic_update_ms_per_frame > 0
                         ? p.bottom_up_update_ms_per_frame / p.kinetic_update_ms_per_frame
                         : 0;
  p.shadow_ms_per_frame = kinetic.shadow();
  p.bottom_up_shadow_ms_per_frame = peers.bottom_up.shadow();
  p.embree_refit_shadow_ms_per_frame = peers.refit.shadow();
  p.embree_rebuild_shadow_ms_per_frame = peers.rebuild.shadow();
  p.total_ms_per_frame = p.kinetic_update_ms_per_frame + p.shadow_ms_per_frame;
  p.bottom_up_total_ms_per_frame =
      p.bottom_up_update_ms_per_frame + p.bottom_up_shadow_ms_per_frame;
  p.embree_refit_total_ms_per_frame =
      p.embree_refit_update_ms_per_frame + p.embree_refit_shadow_ms_per_frame;
  p.embree_rebuild_total_ms_per_frame =
      p.embree_rebuild_update_ms_per_frame + p.embree_rebuild_shadow_ms_per_frame;
  p.build_ms = kinetic.runs.front().build_ms;
  const auto& masks = kinetic.runs.front().masks;
  for (size_t f = 0; f < masks.size(); ++f)
    for (size_t i = 0; i < masks[f].size(); ++i) {
      if (masks[f][i] != peers.bottom_up.runs.front().masks[f][i])
        throw std::runtime_error("kinray bench: the " + p.tree +
                                 " tree and the bottom-up tree disagree on a shadow ray");
      p.embree_mask_mismatches += masks[f][i] != peers.refit.runs.front().masks[f][i];
    }
  p.stats = s;
}

std::vector<TreeBenchPoint> measure(const TreeBenchParams& bench, const std::string& sweep,
                                    const std::string& scene, int inbetweens) {
  RenderParams params = bench.base;
  params.scene = scene;
  params.frames.reset();
  params.fps.reset();
  params.inbetweens = inbetweens;
  params.backend = "embree";
  params.quiet = true;
  RenderJob job(params);
  const std::vector<double>& times = job.frame_times();
  const CameraSpaceScene& cs = job.camera_space();
  const std::vector<size_t> timed = spread(times.size(), bench.shadow_frames);
  std::vector<std::vector<ShadowRay>> rays;
  {
    const std::unique_ptr<Backend> primary = make_backend("embree", cs, backend_config(params));
    Frame frame;
    for (size_t f : timed) {
      primary->render(times[f], frame);
      rays.push_back(shadow_rays(frame, PixelRays{params.width, params.height}));
    }
  }
  auto measure_tracer = [&](auto make) {
    Measured m;
    for (int r = 0; r < bench.repetitions; ++r) {
      const std::unique_ptr<ShadowTracer> tracer = make();
      m.runs.push_back(run(*tracer, times, timed, rays));
    }
    return m;
  };
  Peers peers;
  peers.bottom_up =
      measure_tracer([&] { return make_tree_shadow_tracer(cs, ShadowTree::refit, false); });
  peers.refit = measure_tracer(
      [&] { return std::make_unique<EmbreeShadowTracer>(cs, EmbreeShadowTracer::Update::kRefit); });
  peers.rebuild = measure_tracer([&] {
    return std::make_unique<EmbreeShadowTracer>(cs, EmbreeShadowTracer::Update::kRebuild);
  });

  std::vector<TreeBenchPoint> points;
  const size_t intervals = std::max<size_t>(1, (times.size() - 1) / size_t(inbetweens));
  for (ShadowTree kind : bench.structures) {
    const Measured kinetic =
        measure_tracer([&] { return make_tree_shadow_tracer(cs, kind, false); });
    TreeBenchPoint p;
    p.sweep = sweep;
    p.scene = scene;
    p.tree = shadow_tree_name(kind);
    p.inbetweens = inbetweens;
    p.triangles = cs.triangle_count();
    p.frames = times.size();
    p.key_intervals = intervals;
    for (const auto& r : rays)
      p.shadow_rays_per_frame = std::max(p.shadow_rays_per_frame, r.size());
    fill_measurements(p, kinetic, peers);
    points.push_back(std::move(p));
  }
  return points;
}

}  // namespace

TreeBenchReport run_tree_benchmark(const TreeBenchParams& params,
                                   const std::function<void(const std::string&)>& progress) {
  struct Configuration {
    std::string sweep, scene;
    int inbetweens;
  };
  std::vector<Configuration> configurations;
  for (int k : params.inbetweens) configurations.push_back({"inbetweens", params.base.scene, k});
  const int sweep_k =
      std::find(params.inbetweens.begin(), params.inbetweens.end(), 16) != params.inbetweens.end()
          ? 16
          : params.inbetweens.back();
  for (int n : params.triangles)
    configurations.push_back({"triangles", with_triangles(params.base.scene, n), sweep_k});
  TreeBenchReport report;
  for (size_t c = 0; c < configurations.size(); ++c) {
    const Configuration& config = configurations[c];
    if (progress)
      progress("[" + std::to_string(c + 1) + "/" + std::to_string(configurations.size()) + "] " +
               config.sweep + ": " + config.scene + ", " + std::to_string(config.inbetweens) +
               " in-betweens");
    for (TreeBenchPoint& p : measure(params, config.sweep, config.scene, config.inbetweens))
      report.points.push_back(std::move(p));
  }
  return report;
}

}  // namespace kinray
