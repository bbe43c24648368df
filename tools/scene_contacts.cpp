#include "tools/scene_contacts.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "kinetic/collision/swept_volume_hierarchy.h"
#include "scenes/error.h"

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

}  // namespace

ContactStructure parse_contact_structure(const std::string& text) {
  if (text == "swept") return ContactStructure::swept;
  if (text == "brute") return ContactStructure::brute;
  throw InputError("--structure", "expected swept or brute, got '" + text + "'");
}

SceneContacts find_scene_contacts(const Scene& scene, const CollideParams& params) {
  std::vector<std::uint32_t> objects = params.objects;
  if (objects.empty())
    for (std::uint32_t o = 0; o < scene.objects.size(); ++o) objects.push_back(o);
  for (std::uint32_t o : objects)
    if (o >= scene.objects.size())
      throw InputError("--objects", "object " + std::to_string(o) +
                                        " out of range (the scene has " +
                                        std::to_string(scene.objects.size()) + " objects)");
  const double begin = std::max(params.time_begin, scene.time_begin);
  const double end = std::min(params.time_end, scene.time_end);
  if (!(begin < end)) throw InputError("--time", "the window does not overlap the shot");

  SceneContacts result;
  const auto clock_start = std::chrono::steady_clock::now();
  const std::vector<double> times = segment_times(scene, objects, begin, end);
  result.segments = times.size() - 1;
  const std::size_t n = objects.size();
  std::vector<std::vector<Vec3>> start(n), finish(n);
  std::vector<MeshSegment> meshes(n);
  std::vector<SweptVolumeHierarchy> hierarchies(n);
  for (std::size_t i = 0; i < n; ++i) positions_at(scene.objects[objects[i]], times[0], finish[i]);
  for (std::size_t s = 0; s + 1 < times.size(); ++s) {
    const double t0 = times[s], t1 = times[s + 1];
    for (std::size_t i = 0; i < n; ++i) {
      const Object& object = scene.objects[objects[i]];
      std::swap(start[i], finish[i]);
      positions_at(object, t1, finish[i]);
      meshes[i] = {objects[i], object.triangles, start[i], finish[i]};
      if (params.structure == ContactStructure::swept) hierarchies[i].update(meshes[i]);
    }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = params.self ? i : i + 1; j < n; ++j) {
        // i == j: the same MeshSegment object on both sides means self-contacts
        if (params.structure == ContactStructure::swept)
          hierarchies[j].contacts(meshes[i], meshes[j], t0, t1, result.contacts, result.counters);
        else
          brute_force_contacts(meshes[i], meshes[j], t0, t1, result.contacts, result.counters);
      }
  }
  sort_contacts(result.contacts);
  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - clock_start).count();
  return result;
}

}  // namespace kinray
