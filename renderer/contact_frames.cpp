#include "renderer/contact_frames.h"

#include <algorithm>
#include <array>
#include <initializer_list>

#include "renderer/contact_tint.h"
#include "contacts/scene_contacts.h"

namespace kinray {
namespace {

/// The triangles around each vertex of an object, built for the objects that have contacts.
class TrianglesAround {
 public:
  explicit TrianglesAround(const Scene& scene) : m_scene(scene), m_around(scene.objects.size()) {}

  /// Appends the keys of the triangles of `object` that hold every vertex of `corners`.
  void append(uint32_t object, std::initializer_list<uint32_t> corners,
              std::vector<uint64_t>& out) {
    const Object& mesh = m_scene.objects[object];
    std::vector<std::vector<uint32_t>>& around = m_around[object];
    if (around.empty()) {
      around.resize(mesh.vertex_count());
      for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
        for (uint32_t v : mesh.triangles[t]) around[v].push_back(t);
    }
    for (uint32_t t : around[*corners.begin()]) {
      const Triangle& tri = mesh.triangles[t];
      if (std::all_of(corners.begin(), corners.end(),
                      [&](uint32_t v) { return tri[0] == v || tri[1] == v || tri[2] == v; }))
        out.push_back(triangle_key(object, t));
    }
  }

  void append(const Contact& contact, std::vector<uint64_t>& out) {
    const std::array<uint32_t, 4>& v = contact.vertices;
    if (contact.type == ContactType::vertex_face) {
      append(contact.objects[0], {v[0]}, out);
      append(contact.objects[1], {v[1], v[2], v[3]}, out);
    } else {
      append(contact.objects[0], {v[0], v[1]}, out);
      append(contact.objects[1], {v[2], v[3]}, out);
    }
  }

 private:
  const Scene& m_scene;
  std::vector<std::vector<std::vector<uint32_t>>> m_around;  ///< [object][vertex] -> triangles
};

}  // namespace

std::vector<std::vector<uint64_t>> contact_tint_frames(const Scene& scene,
                                                       const std::vector<double>& frame_times,
                                                       const FrameSlice& slice) {
  std::vector<std::vector<uint64_t>> frames(frame_times.size());
  if (slice.size() == 0) return frames;
  const std::vector<double> bounds =
      contact_window_bounds(frame_times, scene.time_begin, scene.time_end);
  CollideParams params;
  params.self = true;
  params.time_begin = bounds[slice.begin];
  params.time_end = bounds[slice.end];
  const SceneContacts found = find_scene_contacts(scene, params);
  TrianglesAround around(scene);
  for (const Contact& contact : found.contacts) {
    // the window holding contact.time: the last bound at or before it (the last window closed)
    const auto after = std::upper_bound(bounds.begin(), bounds.end(), contact.time);
    size_t frame = size_t(after - bounds.begin());
    if (frame == 0) continue;
    frame = std::min(frame - 1, frame_times.size() - 1);
    if (frame < slice.begin || frame >= slice.end) continue;
    around.append(contact, frames[frame]);
  }
  for (std::vector<uint64_t>& keys : frames) {
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  }
  return frames;
}

}  // namespace kinray
