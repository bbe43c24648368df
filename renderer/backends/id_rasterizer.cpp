#include "renderer/backends/id_rasterizer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <nlohmann/json.hpp>

#include "util/input_error.h"

namespace kinray {

TriangleIds::TriangleIds(const CameraSpaceScene& scene) {
  m_first.reserve(scene.objects.size() + 1);
  uint64_t next = 1;
  for (size_t o = 0; o < scene.objects.size(); ++o) {
    m_first.push_back(uint32_t(next));
    next += scene.triangles(o).size();
    // 0xFFFFFFFF stays unused so that "one past the last" fits in 32 bits as well.
    if (next > 0xFFFFFFFFull)
      throw InputError(scene.scene->name, "the scene has " +
                                              std::to_string(scene.triangle_count()) +
                                              " triangles; the rasterizing reference names at most "
                                              "2^32 - 2 with its 32-bit IDs");
  }
  m_first.push_back(uint32_t(next));
}

void TriangleIds::decode(uint32_t id, uint32_t& object, uint32_t& prim) const {
  // The object is the last one whose first id is <= id.
  const auto it = std::upper_bound(m_first.begin(), m_first.end(), id);
  object = uint32_t(it - m_first.begin()) - 1;
  prim = id - m_first[object];
}

RasterBackend::RasterBackend(const CameraSpaceScene& scene, const BackendConfig& config,
                             std::unique_ptr<IdRasterizer> rasterizer)
    : m_scene(scene), m_config(config), m_rasterizer(std::move(rasterizer)), m_ids(scene) {
  if (config.width <= 0 || config.height <= 0)
    throw OptionError("width", "the image size must be positive, not " +
                                   std::to_string(config.width) + "x" +
                                   std::to_string(config.height));
  if (config.width > m_rasterizer->max_size() || config.height > m_rasterizer->max_size())
    throw OptionError("width", "the " + m_rasterizer->name() + " backend renders at most " +
                                   std::to_string(m_rasterizer->max_size()) +
                                   " pixels per side, not " + std::to_string(config.width) + "x" +
                                   std::to_string(config.height));
  m_positions.resize(scene.objects.size());
}

void RasterBackend::render(double t, Frame& frame) {
  const auto start = std::chrono::steady_clock::now();
  frame.resize(m_config.width, m_config.height);
  frame.time = t;

  double z_max = 0;
  for (size_t o = 0; o < m_scene.objects.size(); ++o) {
    const CameraSpaceObject& object = m_scene.objects[o];
    if (!object.visible(t)) continue;
    object.positions_at(t, m_positions[o]);
    for (const Vec3& p : m_positions[o]) z_max = std::max(z_max, p.z());
  }
  if (!(z_max > 0)) return;  // nothing in front of the eye

  // 1e-7 of the farthest depth is below the resolution of float vertex coordinates there, so the
  // near plane clips only what lies practically in the eye plane; with the reversed float depth
  // its value costs no precision.
  const float near = float(z_max * 1e-7);
  const double aspect = double(m_config.width) / double(m_config.height);
  m_clip.clear();
  m_batch_ids.clear();
  for (size_t o = 0; o < m_scene.objects.size(); ++o) {
    if (!m_scene.objects[o].visible(t)) continue;
    const std::vector<Vec3>& p = m_positions[o];
    const std::vector<Triangle>& triangles = m_scene.triangles(o);
    for (size_t prim = 0; prim < triangles.size(); ++prim) {
      const Triangle& tri = triangles[prim];
      // Wholly behind the near plane: GL would clip it away entirely.
      if (p[tri[0]].z() < near && p[tri[1]].z() < near && p[tri[2]].z() < near) continue;
      for (uint32_t v : tri)
        m_clip.emplace_back(float(p[v].x() / aspect), float(p[v].y()), near, float(p[v].z()));
      m_batch_ids.push_back(m_ids.id(uint32_t(o), uint32_t(prim)));
    }
  }
  m_triangles_sent += m_batch_ids.size();
  ++m_frames;
  if (!m_batch_ids.empty()) {
    m_rasterizer->rasterize(RasterBatch{m_config.width, m_config.height, m_clip, m_batch_ids},
                            m_image);
    for (size_t i = 0; i < frame.pixel_count(); ++i) {
      if (m_image.id[i] == 0) continue;
      m_ids.decode(m_image.id[i], frame.object[i], frame.prim[i]);
      frame.depth[i] = float(double(near) / double(m_image.depth[i]));
    }
  }
  m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void RasterBackend::write_stats(nlohmann::json& stats) const {
  stats[name()] = {
      {"frames", m_frames}, {"triangles_rasterized", m_triangles_sent}, {"seconds", m_seconds}};
}

}  // namespace kinray
