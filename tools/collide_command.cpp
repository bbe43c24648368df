// kinray collide SCENE: every contact between (and with --self, within) the scene's animated
// meshes, in time order, found by exact continuous collision detection on each flightplan
// segment (kinetic/collision/), with the kinetic separation list, swept volumes or brute force.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "renderer/job/frame_schedule.h"
#include "renderer/output/image_io.h"
#include "renderer/output/stats_json.h"
#include "scenes/scene_loader.h"
#include "tools/cli_options.h"
#include "tools/commands.h"
#include "tools/json_output.h"
#include "contacts/scene_contacts.h"
#include "util/input_error.h"

namespace kinray {
namespace {

struct CollideOptions {
  RenderOptions scene;  ///< SCENE, --animation, --keyrate
  bool self = false, stats = false, quiet = false, audit = false;
  int checks = 1;
  std::string objects, time, json, structure = "ksl";
};

/// "A,B,...": object indices or names.
std::vector<std::uint32_t> parse_objects(const std::string& text, const Scene& scene) {
  std::vector<std::uint32_t> objects;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t comma = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, comma - begin);
    begin = comma + 1;
    std::int64_t index = -1;
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o)
      if (scene.objects[o].name == item) index = o;
    if (index < 0 && !item.empty() && item.find_first_not_of("0123456789") == std::string::npos)
      index = std::stoll(item.substr(0, 9));
    if (index < 0 || index >= std::int64_t(scene.objects.size()))
      throw InputError("--objects", "'" + item + "' is neither an object name nor an index below " +
                                        std::to_string(scene.objects.size()));
    objects.push_back(std::uint32_t(index));
  }
  return objects;
}

nlohmann::json to_json(const Contact& c) {
  return {{"time", c.time},
          {"type", contact_type_name(c.type)},
          {"objects", c.objects},
          {"vertices", c.vertices},
          {"point", {c.point.x(), c.point.y(), c.point.z()}}};
}

nlohmann::json ksl_json(const KslReport& k) {
  const KslEventCounts& e = k.list.events;
  QualityCounts q;
  q.certificates_live_max = k.list.certificates_live_max;
  q.certificates_live = k.list.certificates_live;
  q.certificates_computed = k.list.certificates_computed;
  q.events = e.total();
  q.events_external = e.external();
  q.events_internal = e.total() - e.external();
  q.objects_present = k.list.triangles;
  return {{"events", event_counts_json(e)},
          {"events_external", q.events_external},
          {"events_internal", q.events_internal},
          {"certificates",
           section_json([&](auto visit) { k.list.for_each_certificate_counter(visit); })},
          {"list", section_json([&](auto visit) { k.list.for_each_list_counter(visit); })},
          {"quality", quality_json(q)},
          {"trees",
           {{"leaf_events", k.trees.events.leaf},
            {"tree_events", k.trees.events.tree},
            {"flightplan_events", k.trees.events.flightplan},
            {"realizer_changes", k.trees.realizer_changes},
            {"nodes_woken", k.trees.nodes_woken},
            {"nodes", k.trees.nodes}}},
          {"pad", k.pad}};
}

nlohmann::json stats_json(const SceneContacts& r) {
  nlohmann::json stats = {{"segments", r.segments},
                          {"object_segments", r.counters.segments},
                          {"node_visits", r.counters.node_visits},
                          {"triangle_pairs", r.counters.triangle_pairs}};
  stats.update(counters_json(r.counters.primitives));
  if (r.ksl) stats["ksl"] = ksl_json(*r.ksl);
  return stats;
}

void run_collide(const CollideOptions& options) {
  CollideParams params;
  params.structure = parse_contact_structure(options.structure);
  params.self = options.self;
  params.audit = options.audit;
  if (params.audit && params.structure != ContactStructure::ksl)
    throw InputError("--audit",
                     "applies to --structure ksl only (the separation list and its "
                     "trees), and this run uses " +
                         options.structure + " (--audit would be ignored)");
  params.checks = options.checks;
  if (!options.time.empty())
    std::tie(params.time_begin, params.time_end) = parse_time_range(options.time);
  prepare_json_output(options.json);
  const Scene scene = load_scene(options.scene.params.scene, model_options(options.scene.params));
  if (!options.objects.empty()) params.objects = parse_objects(options.objects, scene);
  const SceneContacts result = find_scene_contacts(scene, params);

  std::size_t vf = 0;
  for (const Contact& c : result.contacts) {
    vf += c.type == ContactType::vertex_face;
    if (options.quiet) continue;
    std::printf("%.9f %s objects %u %u vertices %u %u %u %u point %.9g %.9g %.9g\n", c.time,
                contact_type_name(c.type), c.objects[0], c.objects[1], c.vertices[0], c.vertices[1],
                c.vertices[2], c.vertices[3], c.point.x(), c.point.y(), c.point.z());
  }
  std::printf("collide %s: %zu contacts (%zu vf, %zu ee) over %zu segments, %s, %.1f ms\n",
              options.scene.params.scene.c_str(), result.contacts.size(), vf,
              result.contacts.size() - vf, result.segments, options.structure.c_str(),
              1e3 * result.seconds);
  if (options.stats) std::printf("%s\n", stats_json(result).dump(2).c_str());
  if (options.json.empty()) return;
  nlohmann::json contacts = nlohmann::json::array();
  for (const Contact& c : result.contacts) contacts.push_back(to_json(c));
  const nlohmann::json report = {{"scene", options.scene.params.scene},
                                 {"structure", options.structure},
                                 {"self", options.self},
                                 {"contacts", contacts},
                                 {"ms", 1e3 * result.seconds},
                                 {"stats", stats_json(result)}};
  write_file_atomically(options.json, report.dump(1) + "\n");
}

}  // namespace

void register_collide_command(CLI::App& app) {
  auto options = std::make_shared<CollideOptions>();
  CLI::App* command = app.add_subcommand(
      "collide", "Every contact between (--self: also within) the animated meshes, in time order");
  add_scene_options(*command, options->scene);
  command->add_flag("--self", options->self, "Also contacts of each object with itself");
  command->add_option("--objects", options->objects,
                      "Only these objects: names or indices A,B,...");
  add_time_option(*command, options->time, "Only contacts in [A, B] seconds, given as A:B");
  command->add_option("--structure", options->structure, "ksl | swept | brute")
      ->capture_default_str();
  command->add_option("--checks", options->checks,
                      "Collision checks per flightplan segment (swept volumes run per check)")
      ->capture_default_str();
  command->add_flag("--audit", options->audit,
                    "ksl: audit the separation list and its trees after every advance");
  command->add_option("--json", options->json, "Write every contact and the counters as JSON");
  command->add_flag("--stats", options->stats, "Print the counters");
  command->add_flag("-q,--quiet", options->quiet, "Only the summary line");
  command->callback([options] { run_collide(*options); });
}

}  // namespace kinray
