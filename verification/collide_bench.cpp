#include "verification/collide_bench.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "contacts/scene_contacts.h"
#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "scenes/scene_loader.h"
#include "util/input_error.h"
#include "verification/bench_support.h"
#include "verification/benchmark.h"
#include "verification/chart.h"

namespace kinray {
namespace {

std::vector<ContactStructure> parse_structures(const std::string& text) {
  std::vector<ContactStructure> out;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) out.push_back(parse_contact_structure(item));
  if (out.empty()) throw InputError("--structure", "names no structure");
  return out;
}

struct Measured {
  double ms = 0;
  SceneContacts result;
};

/// The median time of `repetitions` runs (the contacts of the last).
Measured measure(const Scene& scene, CollideParams params, int repetitions) {
  std::vector<double> ms;
  Measured m;
  for (int r = 0; r < repetitions; ++r) {
    m.result = find_scene_contacts(scene, params);
    ms.push_back(1e3 * m.result.seconds);
  }
  std::ranges::sort(ms);
  m.ms = ms[ms.size() / 2];
  return m;
}

/// One configuration: every structure on the same scene and checks; the contact sets compared.
void run_configuration(const std::string& spec, const std::string& sweep, int checks,
                       const std::vector<ContactStructure>& structures, int repetitions,
                       nlohmann::json& points, bool quiet) {
  const Scene scene = load_scene(spec, ModelOptions{});
  CollideParams params;
  params.self = scene.objects.size() == 1;  // a cloth collides with itself, objects with others
  params.checks = checks;
  size_t triangles = 0;
  for (const Object& o : scene.objects) triangles += o.triangles.size();
  std::map<ContactStructure, Measured> runs;
  for (ContactStructure s : structures) {
    params.structure = s;
    runs[s] = measure(scene, params, repetitions);
  }
  const Measured& first = runs.begin()->second;
  for (const auto& [s, m] : runs)
    if (m.result.contacts != first.result.contacts)
      throw std::runtime_error(std::string("bench: ") + contact_structure_name(s) +
                               " and another structure report different contacts on " + spec);
  const auto swept = runs.find(ContactStructure::swept);
  for (const auto& [s, m] : runs) {
    const double frames = double(m.result.segments) * checks;
    const double contacts_per_check = double(m.result.contacts.size()) / frames;
    nlohmann::json p = {{"sweep", sweep},
                        {"scene", spec},
                        {"structure", contact_structure_name(s)},
                        {"interpolated_frames", checks},
                        {"triangles", triangles},
                        {"segments", m.result.segments},
                        {"ms", m.ms},
                        {"ms_per_frame", m.ms / frames},
                        {"contacts", m.result.contacts.size()},
                        {"contacts_per_check", contacts_per_check},
                        {"triangle_pairs", m.result.counters.triangle_pairs}};
    p["speedup_vs_swept"] = swept != runs.end() ? swept->second.ms / m.ms : 0.0;
    if (m.result.ksl) p["ksl_events"] = m.result.ksl->list.events.total();
    if (!quiet)
      std::fprintf(stderr,
                   "%-6s %-40s checks %4d: %10.2f ms, %8.4f ms/frame, %zu contacts (%.3g per "
                   "check), %.1fx\n",
                   contact_structure_name(s), spec.c_str(), checks, m.ms, m.ms / frames,
                   m.result.contacts.size(), contacts_per_check,
                   p["speedup_vs_swept"].get<double>());
    points.push_back(p);
  }
}

/// Per sweep: the time per check of every structure, and the speedup against swept volumes.
std::vector<std::string> write_collide_charts(const std::string& scene,
                                              const nlohmann::json& points,
                                              const std::string& folder) {
  std::filesystem::create_directories(folder);
  const std::vector<Eigen::Vector3f> palette = {
      {0.85f, 0.33f, 0.1f}, {0.0f, 0.45f, 0.74f}, {0.47f, 0.67f, 0.19f}};
  std::string stem = scene;
  for (char& c : stem)
    if (c == ':' || c == ',' || c == '=' || c == '/') c = '_';
  std::vector<std::string> written;
  for (const char* sweep : {"interpolated_frames", "triangles"}) {
    const bool by_checks = std::string(sweep) == "interpolated_frames";
    std::map<std::string, ChartSeries> time, speedup;
    for (const nlohmann::json& p : points) {
      if (p["sweep"] != sweep) continue;
      const std::string structure = p["structure"];
      const double x =
          by_checks ? p["interpolated_frames"].get<double>() : p["triangles"].get<double>();
      const Eigen::Vector3f color = structure == "ksl"     ? palette[0]
                                    : structure == "swept" ? palette[1]
                                                           : palette[2];
      for (auto* chart : {&time, &speedup}) {
        if (chart == &speedup && structure == "swept") continue;
        ChartSeries& s = (*chart)[structure];
        s.label = structure == "ksl"     ? "kinetic separation list"
                  : structure == "swept" ? "swept volumes"
                                         : "brute force";
        s.color = color;
        s.x.push_back(x);
        s.y.push_back(chart == &time ? p["ms_per_frame"].get<double>()
                                     : p["speedup_vs_swept"].get<double>());
      }
    }
    if (time.empty()) continue;
    const std::string x_label = by_checks ? "collision checks per keyframe interval" : "triangles";
    Chart chart{
        scene + ": time per collision check", x_label, "ms per check", true, true, {}, {}, {}};
    for (auto& [name, s] : time) chart.series.push_back(s);
    const std::string base = folder + "/collide_" + stem + "_" + sweep;
    write_chart_png(chart, base + "_time.png");
    written.push_back(base + "_time.png");
    if (speedup.empty()) continue;
    Chart ratio{scene + ": speedup against swept volumes",
                x_label,
                "swept time / time",
                true,
                true,
                {},
                {},
                {}};
    for (auto& [name, s] : speedup) ratio.series.push_back(s);
    write_chart_png(ratio, base + "_speedup.png");
    written.push_back(base + "_speedup.png");
  }
  return written;
}

}  // namespace

void run_collide_bench(const std::string& scene, const std::string& structures,
                       const std::string& inbetweens, const std::string& triangles, int repetitions,
                       const std::string& json, const std::string& charts, bool quiet) {
  const std::vector<ContactStructure> list = parse_structures(structures);
  const std::vector<int> checks = parse_int_list(inbetweens, "--inbetweens");
  const std::vector<int> counts =
      triangles.empty() ? std::vector<int>{} : parse_int_list(triangles, "--triangles");
  if (repetitions < 1) throw InputError("--repetitions", "must be at least 1");
  if (!counts.empty() && !builtin_scene_params(scene).has_value())
    throw InputError("--triangles", "sweeps the triangles= parameter of a built-in scene, and '" +
                                        scene + "' is not one");
  if (!json.empty()) check_output_file(json, "--json");
  if (!charts.empty()) check_output_folder(charts, "--charts");
  nlohmann::json points = nlohmann::json::array();
  for (int k : checks) run_configuration(scene, "interpolated_frames", k, list, repetitions, points, quiet);
  for (int n : counts)
    run_configuration(with_triangles(scene, n), "triangles", checks.back(), list, repetitions,
                      points, quiet);
  for (const nlohmann::json& p : points)
    std::printf(
        "%s %s interpolated_frames %d triangles %zu: %.4f ms/frame, %zu contacts (%.3g per "
        "check), %.1fx swept\n",
        p["sweep"].get<std::string>().c_str(), p["structure"].get<std::string>().c_str(),
        p["interpolated_frames"].get<int>(), p["triangles"].get<size_t>(),
        p["ms_per_frame"].get<double>(), p["contacts"].get<size_t>(),
        p["contacts_per_check"].get<double>(), p["speedup_vs_swept"].get<double>());
  if (!json.empty())
    write_file_atomically(json, nlohmann::json{{"scene", scene}, {"points", points}}.dump(2) + "\n");
  if (!charts.empty())
    for (const std::string& path : write_collide_charts(scene, points, charts))
      std::printf("chart: %s\n", path.c_str());
}

}  // namespace kinray
