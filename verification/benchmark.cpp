#include "verification/benchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <map>
#include <ostream>
#include <sstream>

#include "renderer/backends/embree_backend.h"
#include "util/input_error.h"
#include "util/parallel.h"
#include "verification/bench_support.h"
#include "verification/chart.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

using Clock = std::chrono::steady_clock;

double elapsed_ms(Clock::time_point since) {
  return std::chrono::duration<double, std::milli>(Clock::now() - since).count();
}

double seconds_at(const nlohmann::json& stats, const char* key) {
  const auto time = stats.find("time_s");
  if (time == stats.end() || !time->contains(key))
    throw std::runtime_error(std::string("the kinetic backend's stats lack time_s.") + key);
  return (*time)[key].get<double>();
}

double event_total(const BenchPoint& p) {
  const auto events = p.kinetic_stats.find("events");
  return events != p.kinetic_stats.end() && events->contains("total")
             ? (*events)["total"].get<double>()
             : 0;
}

struct Configuration {
  std::string sweep, scene;
  int width, height, threads, inbetweens;
};

}  // namespace

BackendRun run_backend(RenderJob& job, const std::function<std::unique_ptr<Backend>()>& make,
                       std::span<const double> times, std::span<const size_t> sampled) {
  BackendRun run;
  run.sampled_frames.resize(sampled.size());
  const auto start = Clock::now();
  std::unique_ptr<Backend> backend = make();
  backend->plan_frames(times);
  Frame frame;
  frame.resize(job.params().width, job.params().height);
  size_t next_sample = 0;
  for (size_t i = 0; i < times.size(); ++i) {
    frame.time = times[i];
    backend->render(times[i], frame);
    if (next_sample < sampled.size() && sampled[next_sample] == i)
      run.sampled_frames[next_sample++] = frame;
  }
  run.wall_ms = elapsed_ms(start);
  backend->write_stats(run.stats);
  return run;
}

namespace {

/// The kinetic side of a point: medians over repetitions of the backend's own timings; returns
/// the first repetition's frames at `sampled`.
std::vector<Frame> measure_kinetic(const BenchParams& bench, RenderJob& job,
                                   const std::vector<double>& times,
                                   const std::vector<size_t>& sampled, BenchPoint& point) {
  std::vector<Frame> kinetic_frames;
  std::vector<double> per_frame, init, events, readout, with_init;
  for (int repetition = 0; repetition < bench.repetitions; ++repetition) {
    BackendRun run = run_backend(
        job, [&] { return job.make_backend("kinetic"); }, times,
        repetition == 0 ? std::span<const size_t>(sampled) : std::span<const size_t>());
    const double frames = double(times.size());
    const double init_ms = 1e3 * seconds_at(run.stats, "init");
    const double events_ms = 1e3 * seconds_at(run.stats, "events");
    const double readout_ms = 1e3 * seconds_at(run.stats, "readout");
    init.push_back(init_ms);
    events.push_back(events_ms / frames);
    readout.push_back(readout_ms / frames);
    per_frame.push_back((events_ms + readout_ms) / frames);
    with_init.push_back((init_ms + events_ms + readout_ms) / frames);
    if (repetition == 0) {
      point.kinetic_stats = std::move(run.stats);
      kinetic_frames = std::move(run.sampled_frames);
    }
  }
  point.kinetic_ms_per_frame = median(per_frame);
  point.kinetic_init_ms = median(init);
  point.kinetic_events_ms = median(events);
  point.kinetic_readout_ms = median(readout);
  point.kinetic_with_init_ms_per_frame = median(with_init);
  return kinetic_frames;
}

/// Every Embree mode on the `sampled` frames (after a warm-up frame), checked against the kinetic
/// frames on the first repetition; the best mode is the fastest median.
void measure_peers(const BenchParams& bench, RenderJob& job, const std::vector<double>& times,
                   const std::vector<size_t>& sampled, const std::vector<Frame>& kinetic_frames,
                   BenchPoint& point) {
  const RenderParams& params = job.params();
  FrameComparator comparator(job.camera_space());
  const std::vector<EmbreeMode> embree_modes =
      bench.embree_modes.empty() ? default_embree_modes(params.threads) : bench.embree_modes;
  for (const EmbreeMode& mode : embree_modes) {
    std::unique_ptr<Backend> backend = make_embree_backend(job, mode);
    Frame frame;
    frame.resize(params.width, params.height);
    frame.time = times[sampled.front()];
    backend->render(frame.time, frame);  // warm-up: the first build of a refit scene
    BenchPoint::Peer peer;
    peer.mode = mode.name();
    std::vector<double> samples;
    for (int repetition = 0; repetition < bench.repetitions; ++repetition) {
      for (size_t s = 0; s < sampled.size(); ++s) {
        frame.time = times[sampled[s]];
        const auto start = Clock::now();
        backend->render(frame.time, frame);
        samples.push_back(elapsed_ms(start));
        if (repetition == 0)
          point.pixels_compared += peer.count(comparator.compare(kinetic_frames[s], frame));
      }
    }
    peer.ms_per_frame = median(samples);
    peer.frames_measured = samples.size();
    point.mismatch_real += peer.mismatch_real;
    point.mismatch_tie += peer.mismatch_tie;
    point.embree.push_back(peer);
  }
  const auto best = std::min_element(point.embree.begin(), point.embree.end(),
                                     [](const auto& a, const auto& b) { return a.ms_per_frame < b.ms_per_frame; });
  if (best != point.embree.end()) {
    point.embree_best_ms_per_frame = best->ms_per_frame;
    point.embree_best_mode = best->mode;
    point.speedup_vs_best_embree =
        point.kinetic_ms_per_frame > 0 ? best->ms_per_frame / point.kinetic_ms_per_frame : 0;
  }
}

/// One Embree scene built from nothing and traced once (the widest packets up to 8 this machine
/// has): what initialisation is set beside. Median over repetitions, in ms.
double measure_first_build(const BenchParams& bench, RenderJob& job, double time) {
  const std::vector<int> widths = embree_packet_widths(job.params().threads);
  const EmbreeMode mode{EmbreeBuild::kRebuild, *std::prev(std::upper_bound(widths.begin(), widths.end(), 8))};
  std::vector<double> first;
  for (int repetition = 0; repetition < bench.repetitions; ++repetition) {
    const auto start = Clock::now();
    std::unique_ptr<Backend> backend = make_embree_backend(job, mode);
    Frame frame;
    frame.resize(job.params().width, job.params().height);
    frame.time = time;
    backend->render(frame.time, frame);
    first.push_back(elapsed_ms(start));
  }
  return median(first);
}

/// --backend auto over the frames of the point, from creating it to the last frame (median over
/// repetitions), set against the faster of what the point measured of each backend.
void measure_auto(const BenchParams& bench, RenderJob& job, const std::vector<double>& times,
                  BenchPoint& point) {
  std::vector<double> wall;
  for (int repetition = 0; repetition < bench.repetitions; ++repetition) {
    BackendRun run = run_backend(job, [&] { return job.make_backend("auto"); }, times, {});
    wall.push_back(run.wall_ms);
    if (repetition == 0 && run.stats.contains("auto"))
      point.auto_summary = run.stats["auto"]["summary"].get<std::string>();
  }
  const double frames = double(times.size());
  point.auto_ms_per_frame = median(wall) / frames;
  const double best_embree = point.embree_build_and_trace_ms +
                             point.embree_best_ms_per_frame * std::max(frames - 1, 0.0);
  point.faster_ms_per_frame =
      std::min(point.kinetic_with_init_ms_per_frame * frames, best_embree) / frames;
}

}  // namespace

size_t BenchPoint::Peer::count(const FrameDiff& diff) {
  mismatch_real += diff.mismatch_real;
  mismatch_tie += diff.mismatch_tie;
  return diff.pixel_count();
}

double BenchPoint::events_per_key_interval() const {
  return key_intervals ? event_total(*this) / double(key_intervals) : 0;
}

std::unique_ptr<Backend> make_embree_backend(const RenderJob& job, const EmbreeMode& mode) {
  BackendConfig config = backend_config(job.params());
  config.embree_build = mode.build;
  config.embree_packet = mode.packet;
  return make_backend("embree", job.camera_space(), config);
}

BenchPoint measure_frames(const BenchParams& bench, RenderJob& job,
                          const std::vector<double>& times, int inbetweens) {
  const RenderParams& params = job.params();
  BenchPoint point;
  point.sweep = "base";
  point.scene = params.scene;
  point.width = params.width;
  point.height = params.height;
  point.threads = resolve_threads(params.threads);
  point.inbetweens = inbetweens;
  point.triangles = job.scene().triangle_count();
  point.frames = times.size();
  point.key_intervals = (times.size() - 1) / size_t(inbetweens);
  const std::vector<size_t> sampled = spread(times.size(), bench.reference_frames);
  const std::vector<Frame> kinetic_frames = measure_kinetic(bench, job, times, sampled, point);
  measure_peers(bench, job, times, sampled, kinetic_frames, point);
  point.embree_build_and_trace_ms = measure_first_build(bench, job, times.front());
  measure_auto(bench, job, times, point);
  return point;
}

namespace {

BenchPoint measure(const BenchParams& bench, const Configuration& config) {
  RenderParams params = bench.base;
  params.scene = config.scene;
  params.width = config.width;
  params.height = config.height;
  // A scene's own image size (BART) applies to the base configuration only, not to a size sweep.
  params.scene_size = params.scene_size && config.sweep != "size";
  params.threads = config.threads;
  params.frames.reset();
  params.fps.reset();
  params.inbetweens = config.inbetweens;
  params.backend = "kinetic";
  params.audit = false;
  params.quiet = true;
  RenderJob job(params);
  BenchPoint point = measure_frames(bench, job, job.frame_times(), config.inbetweens);
  point.sweep = config.sweep;
  return point;
}

/// BenchReport::ns_per_event_one_thread: a one-thread point of the base scene if one was
/// measured (its events per frame are a median over repetitions), else kinetic-only runs of the
/// base configuration on one thread.
std::optional<double> ns_per_event_one_thread(const BenchParams& bench, const std::vector<BenchPoint>& points) {
  for (const BenchPoint& p : points)
    if (p.threads == 1 && p.scene == bench.base.scene && event_total(p) > 0)
      return 1e6 * p.kinetic_events_ms * double(p.frames) / event_total(p);
  RenderParams params = bench.base;
  params.threads = 1;
  params.frames.reset();
  params.fps.reset();
  params.inbetweens = bench.inbetweens.front();
  params.backend = "kinetic";
  params.audit = false;
  params.quiet = true;
  RenderJob job(params);
  std::vector<double> ns;
  for (int repetition = 0; repetition < bench.repetitions; ++repetition) {
    const nlohmann::json stats =
        run_backend(job, [&] { return job.make_backend("kinetic"); }, job.frame_times(), {}).stats;
    const double events = stats["events"]["total"].get<double>();
    if (events > 0) ns.push_back(1e9 * seconds_at(stats, "events") / events);
  }
  if (ns.empty()) return std::nullopt;
  return median(ns);
}

}  // namespace

std::vector<int> parse_int_list(const std::string& text, const std::string& flag) {
  std::vector<int> values;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    size_t used = 0;
    long value = 0;
    try {
      value = std::stol(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size() || value < 1 || value > 100'000'000)
      throw InputError(flag, "expected a comma-separated list of positive whole numbers, got '" + text + "'");
    values.push_back(int(value));
  }
  if (values.empty()) throw InputError(flag, "the list is empty");
  return values;
}

std::vector<EmbreeMode> default_embree_modes(int threads) {
  const std::vector<int> widths = embree_packet_widths(threads);
  std::vector<EmbreeMode> modes;
  for (const EmbreeMode& mode : std::initializer_list<EmbreeMode>{
           {EmbreeBuild::kRebuild, 1},
           {EmbreeBuild::kRebuild, 8},
           {EmbreeBuild::kRefit, 1},
           {EmbreeBuild::kRefit, 4},
           {EmbreeBuild::kRefit, 8},
           {EmbreeBuild::kRefit, 16}})
    if (std::find(widths.begin(), widths.end(), mode.packet) != widths.end()) modes.push_back(mode);
  return modes;
}

std::vector<EmbreeMode> parse_embree_modes(const std::string& text) {
  std::vector<EmbreeMode> modes;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    const size_t slash = item.find('/');
    EmbreeMode mode;
    const std::optional<EmbreeBuild> build = find_enum(kEmbreeBuildNames, item.substr(0, slash));
    if (build) mode.build = *build;
    if (slash != std::string::npos) mode.packet = parse_int_list(item.substr(slash + 1), "--embree-modes").front();
    if (!build || !is_embree_packet_width(mode.packet))
      throw InputError("--embree-modes", "expected BUILD/PACKET items with BUILD rebuild or refit and PACKET 1, 4, 8 or 16, got '" + item + "'");
    modes.push_back(mode);
  }
  if (modes.empty()) throw InputError("--embree-modes", "the list is empty");
  return modes;
}

void validate(const BenchParams& params) {
  validate(params.base);
  if (params.inbetweens.empty()) throw InputError("--inbetweens", "the list is empty");
  const std::vector<int> widths = embree_packet_widths(params.base.threads);
  for (const EmbreeMode& mode : params.embree_modes)
    if (std::find(widths.begin(), widths.end(), mode.packet) == widths.end())
      throw InputError("--embree-modes", "this machine's Embree has no native " +
                                             std::to_string(mode.packet) + "-wide ray packets (" +
                                             mode.name() + ")");
  if (params.repetitions < 1) throw InputError("--repetitions", "must be at least 1");
  if (params.reference_frames < 1) throw InputError("--reference-frames", "must be at least 1");
  if (params.base.frames || params.base.fps)
    throw InputError("--frames/--fps", "bench renders --inbetweens K per keyframe interval; use --time to cut the shot");
  for (int n : params.threads)
    if (n < 1) throw InputError("--threads", "thread counts must be at least 1");
}

BenchReport run_benchmark(const BenchParams& params, const std::function<void(const std::string&)>& progress) {
  validate(params);
  const RenderParams& base = params.base;
  const int sweep_k = std::find(params.inbetweens.begin(), params.inbetweens.end(), 16) != params.inbetweens.end()
                          ? 16
                          : params.inbetweens.back();
  std::vector<Configuration> configurations;
  const std::string sweep_name = params.inbetweens.size() > 1 ? "inbetweens" : "base";
  for (int k : params.inbetweens)
    configurations.push_back({sweep_name, base.scene, base.width, base.height, base.threads, k});
  for (int n : params.triangles)
    configurations.push_back({"triangles", with_triangles(base.scene, n), base.width, base.height, base.threads, sweep_k});
  for (const auto& [w, h] : params.sizes)
    configurations.push_back({"size", base.scene, w, h, base.threads, sweep_k});
  for (int n : params.threads)
    configurations.push_back({"threads", base.scene, base.width, base.height, n, sweep_k});

  BenchReport report;
  for (size_t c = 0; c < configurations.size(); ++c) {
    const Configuration& config = configurations[c];
    if (progress) {
      std::ostringstream line;
      line << "[" << c + 1 << "/" << configurations.size() << "] " << config.scene << " " << config.width << "x"
           << config.height << " threads=" << resolve_threads(config.threads) << " inbetweens=" << config.inbetweens;
      progress(line.str());
    }
    report.points.push_back(measure(params, config));
  }
  report.base_scene = base.scene;
  report.ns_per_event_one_thread = ns_per_event_one_thread(params, report.points);
  return report;
}

nlohmann::json BenchReport::to_json() const {
  nlohmann::json points_json = nlohmann::json::array();
  for (const BenchPoint& p : points) {
    nlohmann::json embree = nlohmann::json::array();
    for (const auto& peer : p.embree)
      embree.push_back({{"mode", peer.mode}, {"ms_per_frame", peer.ms_per_frame},
                        {"frames_measured", peer.frames_measured}, {"mismatch_real", peer.mismatch_real},
                        {"mismatch_tie", peer.mismatch_tie}});
    points_json.push_back({{"sweep", p.sweep},
                           {"scene", p.scene},
                           {"size", std::to_string(p.width) + "x" + std::to_string(p.height)},
                           {"threads", p.threads},
                           {"inbetweens", p.inbetweens},
                           {"triangles", p.triangles},
                           {"frames", p.frames},
                           {"key_intervals", p.key_intervals},
                           {"kinetic_ms_per_frame", p.kinetic_ms_per_frame},
                           {"kinetic_init_ms", p.kinetic_init_ms},
                           {"kinetic_events_ms_per_frame", p.kinetic_events_ms},
                           {"kinetic_readout_ms_per_frame", p.kinetic_readout_ms},
                           {"kinetic_with_init_ms_per_frame", p.kinetic_with_init_ms_per_frame},
                           {"kinetic_events_per_key_interval", p.events_per_key_interval()},
                           {"kinetic_stats", p.kinetic_stats},
                           {"embree", embree},
                           {"embree_best_ms_per_frame", p.embree_best_ms_per_frame},
                           {"embree_best_mode", p.embree_best_mode},
                           {"embree_build_and_trace_ms", p.embree_build_and_trace_ms},
                           {"speedup_vs_best_embree", p.speedup_vs_best_embree},
                           {"best_embree_ms_per_frame", p.embree_best_ms_per_frame},
                           {"kinetic_init_in_embree_frames",
                            p.embree_best_ms_per_frame > 0
                                ? p.kinetic_init_ms / p.embree_best_ms_per_frame
                                : 0.0},
                           {"auto_summary", p.auto_summary},
                           {"auto_ms_per_frame", p.auto_ms_per_frame},
                           {"faster_ms_per_frame", p.faster_ms_per_frame},
                           {"auto_over_faster", p.faster_ms_per_frame > 0
                                                    ? p.auto_ms_per_frame / p.faster_ms_per_frame
                                                    : 0.0},
                           {"pixels_compared", p.pixels_compared},
                           {"mismatch_real", p.mismatch_real},
                           {"mismatch_tie", p.mismatch_tie}});
  }
  nlohmann::json result = {{"points", points_json}};
  if (const auto k = break_even_inbetweens()) result["break_even_inbetweens"] = *k;
  else result["break_even_inbetweens"] = nullptr;
  result["scene"] = base_scene;
  if (ns_per_event_one_thread) result["ns_per_event_one_thread"] = *ns_per_event_one_thread;
  else result["ns_per_event_one_thread"] = nullptr;
  return result;
}

std::string BenchReport::to_csv() const {
  std::ostringstream out;
  out << "sweep,scene,width,height,threads,inbetweens,triangles,frames,backend,ms_per_frame,init_ms,"
         "events_ms_per_frame,readout_ms_per_frame,events_total,mismatch_real,mismatch_tie\n";
  for (const BenchPoint& p : points) {
    const std::string head = p.sweep + ",\"" + p.scene + "\"," + std::to_string(p.width) + "," + std::to_string(p.height) +
                             "," + std::to_string(p.threads) + "," + std::to_string(p.inbetweens) + "," +
                             std::to_string(p.triangles) + "," + std::to_string(p.frames) + ",";
    out << head << "kinetic," << p.kinetic_ms_per_frame << "," << p.kinetic_init_ms << "," << p.kinetic_events_ms << ","
        << p.kinetic_readout_ms << "," << event_total(p) << ",,\n";
    for (const auto& peer : p.embree)
      out << head << "embree " << peer.mode << "," << peer.ms_per_frame << ",,,,," << peer.mismatch_real << ","
          << peer.mismatch_tie << "\n";
  }
  return out.str();
}

std::optional<double> BenchReport::break_even_inbetweens() const {
  std::vector<const BenchPoint*> sweep;
  for (const BenchPoint& p : points)
    if (p.sweep == "inbetweens") sweep.push_back(&p);
  std::sort(sweep.begin(), sweep.end(), [](auto a, auto b) { return a->inbetweens < b->inbetweens; });
  for (size_t k = 0; k < sweep.size(); ++k) {
    const double margin = sweep[k]->embree_best_ms_per_frame - sweep[k]->kinetic_ms_per_frame;
    if (margin < 0) continue;
    if (k == 0) return double(sweep[0]->inbetweens);
    // The previous point was slower: interpolate the crossing in log2 K.
    const double previous = sweep[k - 1]->embree_best_ms_per_frame - sweep[k - 1]->kinetic_ms_per_frame;
    const double a = std::log2(double(sweep[k - 1]->inbetweens)), b = std::log2(double(sweep[k]->inbetweens));
    return std::exp2(a + (b - a) * (-previous) / (margin - previous));
  }
  return std::nullopt;
}

namespace {

using XOf = std::function<double(const BenchPoint&)>;

// The kinetic backend's colour first, then one per Embree mode.
const std::vector<Color> kChartPalette = {{0.85f, 0.33f, 0.1f},  {0.47f, 0.67f, 0.19f}, {0.0f, 0.45f, 0.74f},
                                          {0.49f, 0.18f, 0.56f}, {0.3f, 0.75f, 0.93f},  {0.64f, 0.08f, 0.18f},
                                          {0.5f, 0.5f, 0.5f}};

/// The x axis of a sweep's chart: labels and scales it on `chart`, returns each point's x.
XOf sweep_axis(const std::string& sweep, Chart& chart) {
  XOf x_of;
  if (sweep == "inbetweens") {
    x_of = [](const BenchPoint& p) { return double(p.inbetweens); };
    chart.x_label = "in-betweens per keyframe interval";
    chart.log_x = true;
  } else if (sweep == "triangles") {
    x_of = [](const BenchPoint& p) { return double(p.triangles); };
    chart.x_label = "triangles";
    chart.log_x = true;
  } else if (sweep == "size") {
    x_of = [](const BenchPoint& p) { return double(p.width) * p.height; };
    chart.x_label = "pixels";
    chart.log_x = true;
  } else {
    x_of = [](const BenchPoint& p) { return double(p.threads); };
    chart.x_label = "threads";
  }
  return x_of;
}

/// Time per frame of the sweep's points (sorted by x): the kinetic backend, with and without its
/// initialisation spread over the frames, then every Embree mode of the first point.
std::vector<ChartSeries> frame_time_series(const std::vector<const BenchPoint*>& sweep_points, const XOf& x_of) {
  const std::vector<Color>& palette = kChartPalette;
  const BenchPoint& first = *sweep_points.front();
  ChartSeries kinetic{"kinetic", {}, {}, palette[0]}, kinetic_init{"kinetic + init", {}, {}, palette[0], true};
  std::vector<ChartSeries> peers;
  for (size_t m = 0; m < first.embree.size(); ++m)
    peers.push_back({"embree " + first.embree[m].mode, {}, {}, palette[1 + m % (palette.size() - 1)]});
  for (const BenchPoint* p : sweep_points) {
    kinetic.x.push_back(x_of(*p));
    kinetic.y.push_back(p->kinetic_ms_per_frame);
    kinetic_init.x.push_back(x_of(*p));
    kinetic_init.y.push_back(p->kinetic_with_init_ms_per_frame);
    for (size_t m = 0; m < peers.size() && m < p->embree.size(); ++m) {
      peers[m].x.push_back(x_of(*p));
      peers[m].y.push_back(p->embree[m].ms_per_frame);
    }
  }
  std::vector<ChartSeries> series = {kinetic, kinetic_init};
  series.insert(series.end(), peers.begin(), peers.end());
  return series;
}

/// The triangle sweep's second chart: the kinetic initialisation against one Embree build + trace.
Chart init_chart(const std::string& scene, const std::vector<const BenchPoint*>& sweep_points) {
  Chart init;
  init.title = "Initialisation against one Embree build + trace: " + scene;
  init.x_label = "triangles";
  init.y_label = "ms";
  init.log_x = init.log_y = true;
  ChartSeries kinetic_series{"kinetic init", {}, {}, kChartPalette[0]};
  ChartSeries embree_series{"embree build+trace", {}, {}, kChartPalette[2]};
  for (const BenchPoint* p : sweep_points) {
    kinetic_series.x.push_back(double(p->triangles));
    kinetic_series.y.push_back(p->kinetic_init_ms);
    embree_series.x.push_back(double(p->triangles));
    embree_series.y.push_back(p->embree_build_and_trace_ms);
  }
  init.series = {kinetic_series, embree_series};
  return init;
}

}  // namespace

std::vector<std::string> BenchReport::write_charts(const std::string& folder) const {
  std::filesystem::create_directories(folder);
  std::map<std::string, std::vector<const BenchPoint*>> sweeps;
  for (const BenchPoint& p : points) sweeps[p.sweep].push_back(&p);
  std::vector<std::string> written;
  for (auto& [sweep, sweep_points] : sweeps) {
    if (sweep == "base") continue;
    Chart chart;
    chart.log_y = true;
    chart.y_label = "ms per frame";
    const XOf x_of = sweep_axis(sweep, chart);
    std::sort(sweep_points.begin(), sweep_points.end(), [&](auto a, auto b) { return x_of(*a) < x_of(*b); });
    const BenchPoint& first = *sweep_points.front();
    // The triangle sweep varies the scene's parameters: its charts name the scene alone.
    const std::string scene =
        sweep == "triangles" ? first.scene.substr(0, first.scene.find(':')) : first.scene;
    chart.title = "Time per frame against " + chart.x_label + ": " + scene;
    chart.series = frame_time_series(sweep_points, x_of);
    if (sweep == "inbetweens")
      if (const auto k = break_even_inbetweens()) {
        chart.marker_x = *k;
        std::ostringstream label;
        label << "break-even K=" << std::setprecision(2) << *k;
        chart.marker_label = label.str();
      }
    const std::string path = (std::filesystem::path(folder) / ("bench_" + sweep + ".png")).string();
    write_chart_png(chart, path);
    written.push_back(path);

    if (sweep == "triangles") {
      const std::string init_path = (std::filesystem::path(folder) / "bench_init.png").string();
      write_chart_png(init_chart(scene, sweep_points), init_path);
      written.push_back(init_path);
    }
  }
  return written;
}

void BenchReport::print(std::ostream& out) const {
  out << std::fixed;
  out << "sweep       triangles  size        thr   K  frames  kinetic ms/f (events+readout)  init ms  "
         "best embree ms/f (mode)     speedup  events/interval  real  ties\n";
  for (const BenchPoint& p : points) {
    std::ostringstream size;
    size << p.width << "x" << p.height;
    out << std::left << std::setw(11) << p.sweep << " " << std::right << std::setw(9) << p.triangles << "  "
        << std::left << std::setw(10) << size.str() << std::right << std::setw(4) << p.threads << std::setw(4)
        << p.inbetweens << std::setw(8) << p.frames << std::setprecision(3) << std::setw(9) << p.kinetic_ms_per_frame
        << " (" << std::setw(7) << p.kinetic_events_ms << "+" << std::setw(7) << p.kinetic_readout_ms << ")  "
        << std::setprecision(1) << std::setw(8) << p.kinetic_init_ms << std::setprecision(3) << std::setw(10)
        << p.embree_best_ms_per_frame << " (" << std::left << std::setw(10) << p.embree_best_mode << ")" << std::right
        << std::setprecision(2) << std::setw(10) << p.speedup_vs_best_embree << "x" << std::setprecision(0)
        << std::setw(14) << p.events_per_key_interval() << std::setw(8)
        << p.mismatch_real << std::setw(6) << p.mismatch_tie << "\n";
  }
  // --backend auto against the faster backend, whole renders (initialisation and first build in)
  out << "auto:    K  auto ms/f  faster ms/f  auto/faster  rendered with\n";
  for (const BenchPoint& p : points)
    out << std::setprecision(0) << std::setw(10) << p.inbetweens << std::setprecision(3)
        << std::setw(11) << p.auto_ms_per_frame << std::setw(13) << p.faster_ms_per_frame
        << std::setprecision(2) << std::setw(12)
        << (p.faster_ms_per_frame > 0 ? p.auto_ms_per_frame / p.faster_ms_per_frame : 0) << "x  "
        << p.auto_summary << "\n";
  if (const auto k = break_even_inbetweens())
    out << std::setprecision(2) << "break-even: " << *k << " in-betweens per keyframe interval\n";
  if (ns_per_event_one_thread)
    out << std::setprecision(0) << "one thread: " << *ns_per_event_one_thread << " ns per event\n";
  out << std::defaultfloat;
}

}  // namespace kinray
