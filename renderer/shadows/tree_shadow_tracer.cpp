#include "renderer/shadows/tree_shadow_tracer.h"

#include <chrono>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>

#include "kinetic/tree/bottom_up_bvh.h"
#include "kinetic/tree/frame_boxes.h"
#include "kinetic/tree/frame_occlusion.h"
#include "kinetic/tree/kinetic_bvh.h"
#include "renderer/backends/grid_meshes.h"
#include "renderer/shadows/kinetic_shadow_tracer.h"
#include "renderer/output/tree_stats_json.h"

namespace kinray {

namespace {

class TreeShadowTracer final : public ShadowTracer {
 public:
  TreeShadowTracer(const CameraSpaceScene& scene, ShadowTree kind, bool audit)
      : m_scene(scene), m_kind(kind), m_audit(audit) {
    if (kind == ShadowTree::brute)
      throw std::invalid_argument("tree shadow tracer: brute is not a tree");
    for (size_t o = 0; o < scene.objects.size(); ++o) {
      const uint32_t object = scene.objects[o].object;
      if (object >= m_mesh_of_object.size()) m_mesh_of_object.resize(object + 1, UINT32_MAX);
      m_mesh_of_object[object] = uint32_t(o);
    }
  }

  [[nodiscard]] std::string name() const override { return shadow_tree_name(m_kind); }

  void advance_to(double t) override {
    const auto start = std::chrono::steady_clock::now();
    if (m_kind == ShadowTree::refit) {
      if (!m_bottom_up)
        m_bottom_up.emplace(grid_meshes(m_scene), t);
      else
        m_bottom_up->update(t);
    } else if (!m_kinetic) {
      const TreeShape shape = m_kind == ShadowTree::aabb ? TreeShape::aabb : TreeShape::boxtree;
      m_kinetic.emplace(grid_meshes(m_scene), t, KineticBvh::Config{shape, m_audit});
      m_boxes.track(*m_kinetic);
    } else {
      m_kinetic->advance_to(t);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    (m_frames == 0 ? m_build_s : m_update_s) += seconds;
    ++m_frames;
    m_frame = TreeFrame(meshes(), t);
    m_boxes_time = std::nullopt;
  }

  void occluded(std::span<const ShadowRay> rays, std::span<uint8_t> blocked) const override {
    if (m_frames == 0) throw std::logic_error("tree shadow tracer: occluded before advance_to");
    const TreeMeshes& tree_meshes = meshes();
    {  // the frame's boxes, once for every call of the frame (a query cost, timed with them)
      const std::lock_guard<std::mutex> lock(m_boxes_mutex);
      if (m_boxes_time != m_frame.t) {
        if (m_kinetic)
          m_boxes.fill(*m_kinetic, m_frame);
        else
          m_boxes.fill(*m_bottom_up, m_frame);
        m_boxes_time = m_frame.t;
      }
    }
    std::vector<TreeRay> tree_rays(rays.size());
    for (size_t i = 0; i < rays.size(); ++i) {
      const ShadowRay& r = rays[i];
      TreeRay& ray = tree_rays[i];
      ray.origin = r.origin;
      ray.direction = r.direction;
      ray.s_max = r.s_max;
      if (r.object < m_mesh_of_object.size() && m_mesh_of_object[r.object] != UINT32_MAX)
        ray.skip = tree_meshes.triangle_begin(m_mesh_of_object[r.object]) + r.prim;
    }
    frame_occluded(m_boxes, tree_rays, blocked);
  }

  void write_stats(nlohmann::json& stats) const override {
    nlohmann::json& s = stats["shadow_tree"];
    s["kind"] = name();
    s["frames"] = m_frames;
    s["time_s"] = {{"build", m_build_s}, {"update", m_update_s}};
    if (m_kinetic) {
      // Of the updates, the kinetic tree's mesh events (its key passes).
      s["time_s"]["mesh_events"] = m_kinetic->mesh_event_seconds();
      write_kinetic_tree_stats(*m_kinetic, s);
    }
    if (m_bottom_up) write_bottom_up_stats(*m_bottom_up, s);
  }

 private:
  [[nodiscard]] const TreeMeshes& meshes() const {
    return m_kinetic ? m_kinetic->meshes() : m_bottom_up->meshes();
  }

  const CameraSpaceScene& m_scene;
  ShadowTree m_kind;
  bool m_audit = false;
  std::vector<uint32_t> m_mesh_of_object;  ///< Scene object index -> mesh (tree) index
  std::optional<KineticBvh> m_kinetic;
  std::optional<BottomUpBvh> m_bottom_up;
  TreeFrame m_frame;
  mutable std::mutex m_boxes_mutex;  ///< occluded may be called from several threads
  mutable FrameBoxes m_boxes;        ///< filled by the first occluded call of a frame
  mutable std::optional<double> m_boxes_time;
  uint64_t m_frames = 0;
  double m_build_s = 0, m_update_s = 0;
};

}  // namespace

std::unique_ptr<ShadowTracer> make_tree_shadow_tracer(const CameraSpaceScene& scene,
                                                      ShadowTree kind, bool audit) {
  return std::make_unique<TreeShadowTracer>(scene, kind, audit);
}

}  // namespace kinray
