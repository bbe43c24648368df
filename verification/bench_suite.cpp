#include "verification/bench_suite.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <ostream>
#include <sstream>

#include "scenes/procedural.h"
#include "util/input_error.h"
#include "util/parallel.h"

namespace kinray {
namespace {

namespace fs = std::filesystem;

/// BART's scenes in ../shared/data/bart: the suite's name and the file under the BART folder.
const std::vector<std::pair<std::string, std::string>> kBartScenes = {
    {"kitchen", "kitchen/kitchen.aff"}, {"robots", "robots/Robot.aff"}};

bool is_builtin(const std::string& name) {
  const std::vector<std::string> names = builtin_scene_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

std::string known_names() {
  std::string known;
  for (const std::string& n : builtin_scene_names()) known += n + ", ";
  return known + "kitchen, robots";
}

/// The scene's job: its own frame schedule (BART's frame count, else 24 frames) at the suite's
/// size, the kinetic backend's flags, and --keyrate on BART's files only.
RenderParams scene_params(const SuiteParams& params, const SuiteScene& scene) {
  RenderParams p = params.bench.base;
  p.scene = scene.spec;
  p.scene_size = false;
  p.frames.reset();
  p.fps.reset();
  p.inbetweens.reset();
  p.time.reset();
  p.backend = "kinetic";
  p.audit = false;
  p.quiet = true;
  if (is_builtin(scene.name)) p.keyrate = 0;
  return p;
}

/// BART's measure on `job`: its whole schedule once with the kinetic backend and once with the
/// Embree `mode`, the frames compared at `reference_frames` of them spread over the animation.
WholeAnimation measure_whole_animation(const SuiteParams& params, RenderJob& job,
                                       const EmbreeMode& mode) {
  const std::vector<double>& times = job.frame_times();
  const std::vector<size_t> sampled = spread(times.size(), params.bench.reference_frames);
  const BackendRun kinetic = run_backend(
      job, [&] { return job.make_backend("kinetic"); }, times, sampled);
  const BackendRun embree = run_backend(
      job, [&] { return make_embree_backend(job, mode); }, times, sampled);
  WholeAnimation whole;
  whole.frames = times.size();
  whole.kinetic_s = kinetic.wall_ms / 1e3;
  whole.embree_mode = mode.name();
  whole.embree_s = embree.wall_ms / 1e3;
  FrameComparator comparator(job.camera_space());
  for (size_t s = 0; s < sampled.size(); ++s) {
    const FrameDiff diff = comparator.compare(kinetic.sampled_frames[s], embree.sampled_frames[s]);
    whole.mismatch_real += diff.mismatch_real;
    whole.mismatch_tie += diff.mismatch_tie;
  }
  whole.frames_compared = sampled.size();
  return whole;
}

SuiteRow measure_scene(const SuiteParams& params, const SuiteScene& scene,
                       const std::function<void(const std::string&)>& say) {
  say(scene.name + ": loading " + scene.spec);
  RenderJob job(scene_params(params, scene));
  SuiteRow row;
  row.scene = scene;
  row.triangles = job.scene().triangle_count();
  const std::vector<double> keys = job.scene().key_times();
  row.window = suite_window(keys, params.intervals);
  row.report.base_scene = scene.spec;
  for (int k : params.bench.inbetweens) {
    FrameScheduleParams schedule;
    schedule.inbetweens = k;
    schedule.time = row.window;
    const std::vector<double> times = frame_times(keys, schedule);
    std::ostringstream line;
    line << scene.name << ": " << k << " in-betweens, " << times.size() << " frames in ["
         << row.window.first << ", " << row.window.second << "] s";
    say(line.str());
    BenchPoint point = measure_frames(params.bench, job, times, k);
    point.sweep = "inbetweens";
    row.report.points.push_back(std::move(point));
  }
  if (params.whole_animation && !row.report.points.empty()) {
    const BenchPoint& first = row.report.points.front();
    const std::vector<EmbreeMode> modes = params.bench.embree_modes.empty()
                                              ? default_embree_modes(params.bench.base.threads)
                                              : params.bench.embree_modes;
    const EmbreeMode mode = *std::find_if(modes.begin(), modes.end(), [&](const EmbreeMode& m) {
      return m.name() == first.embree_best_mode;
    });
    say(scene.name + ": the whole animation, " + std::to_string(job.frame_times().size()) +
        " frames, kinetic and Embree " + mode.name());
    row.whole = measure_whole_animation(params, job, mode);
  }
  return row;
}

std::string fixed(double value, int digits) {
  std::ostringstream out;
  out << std::fixed << std::setprecision(digits) << value;
  return out.str();
}

}  // namespace

std::vector<SuiteScene> suite_scenes(const std::vector<std::string>& names,
                                     const std::string& bart_folder) {
  std::vector<std::string> chosen = names;
  if (chosen.empty()) {
    chosen = builtin_scene_names();
    for (const auto& [name, file] : kBartScenes) chosen.push_back(name);
  }
  std::vector<SuiteScene> scenes;
  for (const std::string& name : chosen) {
    if (std::any_of(scenes.begin(), scenes.end(),
                    [&](const SuiteScene& s) { return s.name == name; }))
      throw InputError("--scenes", "'" + name + "' is named twice");
    if (is_builtin(name)) {
      scenes.push_back({name, name});
      continue;
    }
    const auto bart = std::find_if(kBartScenes.begin(), kBartScenes.end(),
                                   [&](const auto& b) { return b.first == name; });
    if (bart == kBartScenes.end())
      throw InputError("--scenes", "no suite scene '" + name + "' (known: " + known_names() + ")");
    const fs::path file = fs::path(bart_folder) / bart->second;
    if (!fs::is_regular_file(file))
      throw InputError("--bart",
                       "BART's " + name + " is not at " + file.string() +
                           " (give the folder holding kitchen/ and robots/ with --bart DIR)");
    scenes.push_back({name, file.string()});
  }
  return scenes;
}

size_t SuiteRow::mismatch_real() const {
  size_t real = whole ? whole->mismatch_real : 0;
  for (const BenchPoint& p : report.points) real += p.mismatch_real;
  return real;
}

size_t SuiteReport::mismatch_real() const {
  size_t real = 0;
  for (const SuiteRow& row : rows) real += row.mismatch_real();
  return real;
}

std::pair<double, double> suite_window(const std::vector<double>& key_times, int intervals) {
  // Every animated scene has at least two keys, so the middle one is before the last.
  const size_t last = key_times.size() - 1, middle = last / 2;
  return {key_times[middle], key_times[std::min(last, middle + size_t(std::max(intervals, 1)))]};
}

SuiteReport run_suite(const SuiteParams& params,
                      const std::function<void(const std::string&)>& progress) {
  if (params.scenes.empty()) throw InputError("--scenes", "the list is empty");
  BenchParams checked = params.bench;
  checked.base.scene = params.scenes.front().spec;  // the scenes replace bench's SCENE
  validate(checked);
  SuiteReport report;
  report.width = params.bench.base.width;
  report.height = params.bench.base.height;
  report.threads = resolve_threads(params.bench.base.threads);
  report.intervals = params.intervals;
  report.repetitions = params.bench.repetitions;
  for (size_t s = 0; s < params.scenes.size(); ++s) {
    const std::string prefix =
        "[" + std::to_string(s + 1) + "/" + std::to_string(params.scenes.size()) + "] ";
    report.rows.push_back(measure_scene(params, params.scenes[s], [&](const std::string& line) {
      if (progress) progress(prefix + line);
    }));
  }
  return report;
}

nlohmann::json SuiteReport::to_json() const {
  nlohmann::json rows_json = nlohmann::json::array();
  for (const SuiteRow& row : rows) {
    nlohmann::json speedup = nlohmann::json::object();
    for (const BenchPoint& p : row.report.points)
      speedup[std::to_string(p.inbetweens)] = p.speedup_vs_best_embree;
    nlohmann::json item = {
        {"scene", row.scene.name},
        {"spec", row.scene.spec},
        {"triangles", row.triangles},
        {"window_s", {row.window.first, row.window.second}},
        {"events_per_key_interval",
         row.report.points.empty() ? 0.0 : row.report.points.front().events_per_key_interval()},
        {"speedup_vs_best_embree", speedup},
        {"mismatch_real", row.mismatch_real()},
        {"bench", row.report.to_json()}};
    const std::optional<double> k = row.report.break_even_inbetweens();
    item["break_even_inbetweens"] = k ? nlohmann::json(*k) : nlohmann::json(nullptr);
    if (row.whole)
      item["whole_animation"] = {{"frames", row.whole->frames},
                                 {"kinetic_s", row.whole->kinetic_s},
                                 {"embree_mode", row.whole->embree_mode},
                                 {"embree_s", row.whole->embree_s},
                                 {"frames_compared", row.whole->frames_compared},
                                 {"mismatch_real", row.whole->mismatch_real},
                                 {"mismatch_tie", row.whole->mismatch_tie}};
    rows_json.push_back(item);
  }
  return {{"size", std::to_string(width) + "x" + std::to_string(height)},
          {"threads", threads},
          {"intervals", intervals},
          {"repetitions", repetitions},
          {"rows", rows_json}};
}

void SuiteReport::print(std::ostream& out) const {
  out << "suite: " << width << "x" << height << ", " << threads << " threads, " << intervals
      << (intervals == 1 ? " keyframe interval" : " keyframe intervals")
      << " from each shot's middle key, medians of " << repetitions << "\n";
  std::vector<int> ks;
  if (!rows.empty())
    for (const BenchPoint& p : rows.front().report.points) ks.push_back(p.inbetweens);
  out << std::left << std::setw(14) << "scene" << std::right << std::setw(10) << "triangles"
      << std::setw(16) << "events/interval" << std::setw(12) << "break-even";
  for (int k : ks) out << std::setw(11) << ("K=" + std::to_string(k));
  out << std::setw(8) << "frames" << std::setw(12) << "kinetic s" << std::setw(11) << "embree s"
      << "  " << std::left << std::setw(11) << "(mode)" << std::right << std::setw(6) << "real"
      << std::setw(7) << "ties"
      << "\n";
  for (const SuiteRow& row : rows) {
    const std::optional<double> k = row.report.break_even_inbetweens();
    size_t ties = row.whole ? row.whole->mismatch_tie : 0;
    for (const BenchPoint& p : row.report.points) ties += p.mismatch_tie;
    out << std::left << std::setw(14) << row.scene.name << std::right << std::setw(10)
        << row.triangles << std::setw(16)
        << fixed(row.report.points.empty() ? 0.0
                                           : row.report.points.front().events_per_key_interval(),
                 0)
        << std::setw(12) << (k ? fixed(*k, 1) : "> " + std::to_string(ks.empty() ? 0 : ks.back()));
    for (const BenchPoint& p : row.report.points)
      out << std::setw(10) << fixed(p.speedup_vs_best_embree, 2) << "x";
    if (row.whole)
      out << std::setw(8) << row.whole->frames << std::setw(12) << fixed(row.whole->kinetic_s, 2)
          << std::setw(11) << fixed(row.whole->embree_s, 2) << "  " << std::left << std::setw(11)
          << ("(" + row.whole->embree_mode + ")") << std::right;
    else
      out << std::setw(8) << "-" << std::setw(12) << "-" << std::setw(11) << "-"
          << "  " << std::setw(11) << "";
    out << std::setw(6) << row.mismatch_real() << std::setw(7) << ties << "\n";
  }
  out << "speedup: best Embree ms/frame over kinetic ms/frame (events + read-out) at K in-betweens "
         "per keyframe "
         "interval; break-even: the K from which kinetic is as fast\n";
  if (std::any_of(rows.begin(), rows.end(),
                  [](const SuiteRow& row) { return row.whole.has_value(); }))
    out << "frames, kinetic s, embree s: BART's measure, the whole animation at its frame count, "
           "initialisation included\n";
}

}  // namespace kinray
