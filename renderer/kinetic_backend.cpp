#include "renderer/kinetic_backend.h"

#include <chrono>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "kinetic/grid/frustum_grid.h"
#include "renderer/grid_meshes.h"
#include "renderer/kinetic_shadow_tracer.h"
#include "renderer/kinetic_shutter.h"
#include "renderer/stats_json.h"
#include "util/input_error.h"

namespace kinray {

GridInput kinetic_grid_input(const CameraSpaceScene& scene, int width, int height) {
  GridInput input;
  input.rays = PixelRays{width, height};
  input.meshes = grid_meshes(scene);
  return input;
}

namespace {

class KineticBackend final : public Backend {
 public:
  KineticBackend(const CameraSpaceScene& scene, const BackendConfig& config)
      : m_scene(scene), m_config(config) {
    if (config.width < 1 || config.height < 1) throw OptionError("width", "the image must be at least 1x1");
    m_grid_config.sort = config.sort;
    m_grid_config.threads = config.threads;
    m_grid_config.audit = config.audit;
    m_grid_config.init_progress = &m_init_progress;
    // Primary hits come from the grid; shadow rays, only when there are lights, from the tracer
    // --shadow-tree chooses.
    if (!scene.scene->lights.empty())
      m_shadows = make_kinetic_shadow_tracer(scene, config.shadow_tree, config.audit);
  }

  [[nodiscard]] ShadowTracer* shadow_tracer() override { return m_shadows.get(); }
  [[nodiscard]] const WorkProgress* initialisation_progress() const override {
    return &m_init_progress;
  }

  [[nodiscard]] std::string name() const override { return "kinetic"; }

  void render(double t, Frame& frame) override {
    if (frame.width != m_config.width || frame.height != m_config.height || frame.pixel_count() == 0)
      frame.resize(m_config.width, m_config.height);
    frame.time = t;
    const auto start = std::chrono::steady_clock::now();
    const uint64_t events_before = m_grid ? m_grid->event_count() : 0;
    if (!m_grid) {
      m_grid = std::make_unique<FrustumGrid>(
          kinetic_grid_input(m_scene, m_config.width, m_config.height), t, m_grid_config);
    } else {
      m_grid->advance_to(t);
    }
    const auto advanced = std::chrono::steady_clock::now();
    m_grid->read_out(frame.object, frame.prim, frame.depth);
    const auto done = std::chrono::steady_clock::now();
    m_events_s.push_back(std::chrono::duration<double>(advanced - start).count());
    m_readout_s.push_back(std::chrono::duration<double>(done - advanced).count());
    m_events.push_back(m_grid->event_count() - events_before);
  }

  [[nodiscard]] bool has_motion_blur() const override { return true; }

  void render_shutter(const ShutterWindow& window, Frame& frame) override {
    const auto start = std::chrono::steady_clock::now();
    const uint64_t events_before = m_grid ? m_grid->event_count() : 0;
    if (!m_grid)
      m_grid = std::make_unique<FrustumGrid>(
          kinetic_grid_input(m_scene, m_config.width, m_config.height), window.open, m_grid_config);
    if (!m_shutter)
      m_shutter = std::make_unique<KineticShutter>(m_scene, m_config.shutter.order, m_config.threads);
    m_shutter->render(*m_grid, window, frame);
    m_events_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    m_readout_s.push_back(0);
    m_events.push_back(m_grid->event_count() - events_before);
  }

  void write_stats(nlohmann::json& stats) const override {
    if (m_shadows) m_shadows->write_stats(stats);
    if (!m_grid) return;
    if (m_shutter) {
      const KineticShutterStats& s = m_shutter->stats();
      nlohmann::json& shutter = stats["shutter"] = counters_json(s);
      shutter["order"] = m_shutter->order();
      shutter["events_s"] = s.events_s;
      shutter["integrate_s"] = s.integrate_s;
      shutter["readout_s"] = s.readout_s;
    }
    const GridStats s = m_grid->stats();
    const GridTimings& timings = m_grid->timings();
    stats["events"] = event_counts_json(s.events);
    stats["certificates_live_max"] = s.certificates_live_max;
    stats["memory_bytes_peak"] = m_grid->memory_bytes_peak();
    stats["quality"] = quality_json({s.certificates_live_max, s.certificates_live,
                                     s.certificates_computed, s.events.total(),
                                     s.events_internal, s.events_external, s.triangles_present});
    nlohmann::json& time = stats["time_s"];
    time["init"] = timings.init;
    time["events"] = timings.events;
    time["readout"] = timings.readout;
    nlohmann::json& kinetic = stats["kinetic"] = counters_json(s);
    kinetic["sort"] = depth_sort_name(m_grid_config.sort);
    kinetic["bands"] = m_grid->band_count();
    kinetic["audit"] = m_grid_config.audit;
    kinetic["memory_per_pixel_entry"] =
        s.pixel_entries > 0 ? double(s.pixel_memory_bytes) / double(s.pixel_entries) : 0.0;
    kinetic["per_frame"] = {
        {"events_s", m_events_s}, {"readout_s", m_readout_s}, {"events", m_events}};
  }

 private:
  const CameraSpaceScene& m_scene;
  BackendConfig m_config;
  FrustumGridConfig m_grid_config;
  WorkProgress m_init_progress;  ///< the grid's scan conversion, counted while it is built
  std::unique_ptr<FrustumGrid> m_grid;
  std::unique_ptr<ShadowTracer> m_shadows;  ///< when the scene has lights
  std::unique_ptr<KineticShutter> m_shutter;  ///< motion blur, made by the first render_shutter
  std::vector<double> m_events_s, m_readout_s;
  std::vector<uint64_t> m_events;
};

}  // namespace

std::unique_ptr<Backend> make_kinetic_backend(const CameraSpaceScene& scene, const BackendConfig& config) {
  return std::make_unique<KineticBackend>(scene, config);
}

}  // namespace kinray
