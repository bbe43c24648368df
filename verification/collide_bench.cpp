#include "verification/collide_bench.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "renderer/output/image_io.h"
#include "renderer/output/output_check.h"
#include "scenes/scene_loader.h"
#include "contacts/scene_contacts.h"
#include "util/input_error.h"
#include "verification/bench_support.h"
#include "verification/benchmark.h"

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
    nlohmann::json p = {{"sweep", sweep},
                        {"scene", spec},
                        {"structure", contact_structure_name(s)},
                        {"interpolated_frames", checks},
                        {"triangles", triangles},
                        {"segments", m.result.segments},
                        {"ms", m.ms},
                        {"ms_per_frame", m.ms / frames},
                        {"contacts", m.result.contacts.size()},
                        {"triangle_pairs", m.result.counters.triangle_pairs}};
    p["speedup_vs_swept"] = swept != runs.end() ? swept->second.ms / m.ms : 0.0;
    if (m.result.ksl) p["ksl_events"] = m.result.ksl->list.events.total();
    if (!quiet)
      std::fprintf(stderr, "%-6s %-40s checks %4d: %10.2f ms, %8.4f ms/frame, %zu contacts, %.1fx\n",
                   contact_structure_name(s), spec.c_str(), checks, m.ms, m.ms / frames,
                   m.result.contacts.size(), p["speedup_vs_swept"].get<double>());
    points.push_back(p);
  }
}

}  // namespace

void run_collide_bench(const std::string& scene, const std::string& structures,
                       const std::string& inbetweens, const std::string& triangles,
                       int repetitions, const std::string& json, bool quiet) {
  const std::vector<ContactStructure> list = parse_structures(structures);
  const std::vector<int> checks = parse_int_list(inbetweens, "--inbetweens");
  const std::vector<int> counts =
      triangles.empty() ? std::vector<int>{} : parse_int_list(triangles, "--triangles");
  if (repetitions < 1) throw InputError("--repetitions", "must be at least 1");
  if (!counts.empty() && !builtin_scene_params(scene).has_value())
    throw InputError("--triangles", "sweeps the triangles= parameter of a built-in scene, and '" +
                                        scene + "' is not one");
  if (!json.empty()) check_output_file(json, "--json");
  nlohmann::json points = nlohmann::json::array();
  for (int k : checks) run_configuration(scene, "interpolated_frames", k, list, repetitions, points, quiet);
  for (int n : counts)
    run_configuration(with_triangles(scene, n), "triangles", checks.back(), list, repetitions,
                      points, quiet);
  for (const nlohmann::json& p : points)
    std::printf("%s %s interpolated_frames %d triangles %zu: %.4f ms/frame, %zu contacts, %.1fx swept\n",
                p["sweep"].get<std::string>().c_str(), p["structure"].get<std::string>().c_str(),
                p["interpolated_frames"].get<int>(), p["triangles"].get<size_t>(),
                p["ms_per_frame"].get<double>(), p["contacts"].get<size_t>(),
                p["speedup_vs_swept"].get<double>());
  if (!json.empty())
    write_file_atomically(json, nlohmann::json{{"scene", scene}, {"points", points}}.dump(2) + "\n");
}

}  // namespace kinray
