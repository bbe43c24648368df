#include "contacts/scene_contacts.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "kinetic/collision/kinetic_contact_finder.h"
#include "kinetic/collision/swept_volume_hierarchy.h"
#include "kinetic/motion/welded_triangles.h"
#include "util/input_error.h"

namespace kinray {
namespace {

/// Times at which some selected object's flightplan has a key, inside [begin, end], with both ends.
std::vector<double> segment_times(const Scene& scene, std::span<const std::uint32_t> objects,
                                  double begin, double end) {
  std::vector<double> times = {begin, end};
  for (std::uint32_t o : objects)
    for (double t : scene.objects[o].key_times)
      if (t > begin && t < end) times.push_back(t);
  std::ranges::sort(times);
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

void positions_at(const Object& object, double t, std::vector<Vec3>& out) {
  out.resize(object.vertex_count());
  for (std::uint32_t v = 0; v < out.size(); ++v) out[v] = object.position(v, t);
}

/// The selected objects' positions at both ends of the current segment (every finder tests
/// these), and the object pairs to test, as indices into the selection.
struct SegmentMeshes {
  std::vector<std::vector<Vec3>> start, finish;
  std::vector<VertexTriangles> around;  ///< per selected object, built once
  std::vector<MeshSweep> meshes;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
};

/// Each selected object's flightplans as a FlightplanMesh (positions flattened; the KSL's input)
/// and its triangles with seams welded (welded_triangles.h), which every structure tests: the two
/// sides of a seam are neighbours, not a contact along it all the time.
struct FlightplanMeshes {
  std::vector<std::vector<Vec3>> positions;
  std::vector<std::vector<std::array<std::uint32_t, 3>>> triangles;
  std::vector<FlightplanMesh> meshes;
  FlightplanMeshes(const Scene& scene, std::span<const std::uint32_t> objects) {
    positions.resize(objects.size());
    triangles.resize(objects.size());
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const Object& o = scene.objects[objects[i]];
      positions[i].reserve(o.key_position_sets() * o.vertex_count());
      for (size_t k = 0; k < o.key_position_sets(); ++k)
        for (uint32_t v = 0; v < o.vertex_count(); ++v)
          positions[i].push_back(o.key_position(k, v));
      FlightplanMesh m;
      m.id = objects[i];
      m.key_times = o.key_times;
      m.positions = positions[i];
      m.vertex_count = o.vertex_count();
      m.triangles = o.triangles;
      m.is_static = o.is_static();
      triangles[i] = welded_triangles(m);
      m.triangles = triangles[i];
      meshes.push_back(m);
    }
  }
};

/// Swept volumes with `checks` check intervals on the segment: per interval, every object's
/// swept boxes between its positions at the interval's ends (on the segment's motion), grown by
/// the pad, refitted; the primitive tests on the segment, contacts kept in the interval.
void swept_segment(SegmentMeshes& s, std::vector<SweptVolumeHierarchy>& hierarchies, int checks,
                   double pad, double t0, double t1, SceneContacts& result) {
  std::vector<std::vector<Vec3>> lo(s.meshes.size()), hi(s.meshes.size());
  for (int c = 0; c < checks; ++c) {
    const double u0 = double(c) / checks, u1 = double(c + 1) / checks;
    for (std::size_t i = 0; i < s.meshes.size(); ++i) {
      const MeshSweep& m = s.meshes[i];
      lo[i].resize(m.start.size());
      hi[i].resize(m.start.size());
      for (std::size_t v = 0; v < m.start.size(); ++v) {
        lo[i][v] = m.start[v] + u0 * (m.end[v] - m.start[v]);
        hi[i][v] = c + 1 == checks ? m.end[v] : m.start[v] + u1 * (m.end[v] - m.start[v]);
      }
      hierarchies[i].update({m.object, m.triangles, lo[i], hi[i]}, pad);
    }
    const double w0 = c == 0 ? -kInfinity : t0 + u0 * (t1 - t0);
    const double w1 = c + 1 == checks ? kInfinity : t0 + u1 * (t1 - t0);
    for (const auto& [i, j] : s.pairs)
      hierarchies[j].contacts(hierarchies[i], s.meshes[i], s.meshes[j], t0, t1, w0, w1,
                              result.contacts, result.counters);
  }
}

/// Walks the segments of `times`, filling `s` for each, and calls visit(t0, t1).
template <class Visit>
void walk_segments(const Scene& scene, std::span<const std::uint32_t> objects,
                   const FlightplanMeshes& flightplans, const std::vector<double>& times,
                   SegmentMeshes& s, Visit&& visit) {
  const std::size_t n = objects.size();
  s.start.resize(n);
  s.finish.resize(n);
  s.meshes.resize(n);
  s.around.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const Object& object = scene.objects[objects[i]];
    positions_at(object, times[0], s.finish[i]);
    s.around.emplace_back(flightplans.triangles[i], std::uint32_t(object.vertex_count()));
  }
  for (std::size_t k = 0; k + 1 < times.size(); ++k) {
    for (std::size_t i = 0; i < n; ++i) {
      const Object& object = scene.objects[objects[i]];
      std::swap(s.start[i], s.finish[i]);
      positions_at(object, times[k + 1], s.finish[i]);
      s.meshes[i] = {objects[i], flightplans.triangles[i], s.start[i], s.finish[i], &s.around[i]};
    }
    visit(times[k], times[k + 1]);
  }
}

std::vector<std::uint32_t> selected_objects(const Scene& scene, const CollideParams& params) {
  std::vector<std::uint32_t> objects = params.objects;
  if (objects.empty())
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) objects.push_back(o);
  for (std::uint32_t o : objects)
    if (o >= scene.objects.size())
      throw InputError("--objects", "object " + std::to_string(o) +
                                        " out of range (the scene has " +
                                        std::to_string(scene.objects.size()) + " objects)");
  return objects;
}

}  // namespace

ContactStructure parse_contact_structure(const std::string& text) {
  if (text == "ksl") return ContactStructure::ksl;
  if (text == "swept") return ContactStructure::swept;
  if (text == "brute") return ContactStructure::brute;
  throw InputError("--structure", "expected ksl, swept or brute, got '" + text + "'");
}

const char* contact_structure_name(ContactStructure structure) {
  switch (structure) {
    case ContactStructure::ksl: return "ksl";
    case ContactStructure::swept: return "swept";
    case ContactStructure::brute: break;
  }
  return "brute";
}

SceneContacts find_scene_contacts(const Scene& scene, const CollideParams& params) {
  const std::vector<std::uint32_t> objects = selected_objects(scene, params);
  const double begin = std::max(params.time_begin, scene.time_begin);
  const double end = std::min(params.time_end, scene.time_end);
  if (!(begin < end)) throw InputError("--time", "the window does not overlap the shot");
  if (params.checks < 1) throw InputError("--checks", "must be at least 1");

  SceneContacts result;
  const auto clock_start = std::chrono::steady_clock::now();
  const std::vector<double> times = segment_times(scene, objects, begin, end);
  result.segments = times.size() - 1;
  SegmentMeshes s;
  const std::uint32_t n = std::uint32_t(objects.size());
  for (std::uint32_t i = 0; i < n; ++i)
    for (std::uint32_t j = params.self ? i : i + 1; j < n; ++j) s.pairs.emplace_back(i, j);
  const FlightplanMeshes flightplans(scene, objects);
  const double pad = KineticContactFinder::contact_pad(flightplans.meshes, end);

  if (params.structure == ContactStructure::ksl) {
    KineticContactFinder finder(flightplans.meshes, s.pairs, begin, params.audit);
    walk_segments(scene, objects, flightplans, times, s, [&](double t0, double t1) {
      finder.begin_segment(s.meshes, t0, t1);
      for (int c = 1; c <= params.checks; ++c)
        finder.advance_to(c == params.checks ? t1 : t0 + (t1 - t0) * c / params.checks,
                          result.contacts);
    });
    finder.finish(result.contacts);
    result.counters = finder.counters();
    result.counters.segments = result.segments * s.pairs.size();
    result.ksl = KslReport{finder.stats(), finder.tree_stats(), finder.pad()};
  } else if (params.structure == ContactStructure::swept) {
    std::vector<SweptVolumeHierarchy> hierarchies(n);
    walk_segments(scene, objects, flightplans, times, s, [&](double t0, double t1) {
      swept_segment(s, hierarchies, params.checks, pad, t0, t1, result);
    });
    sort_contacts(result.contacts);
  } else {
    walk_segments(scene, objects, flightplans, times, s, [&](double t0, double t1) {
      for (const auto& [i, j] : s.pairs)  // i == j: the same MeshSweep means self-contacts
        brute_force_contacts(s.meshes[i], s.meshes[j], t0, t1, result.contacts, result.counters);
    });
    sort_contacts(result.contacts);
  }
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace kinray
