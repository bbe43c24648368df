#include "renderer/backends/kinetic_backend.h"

#include <chrono>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "kinetic/grid/frustum_grid.h"
#include "kinetic/squares/pixel_square_sets.h"
#include "renderer/antialiasing/exact_pixel.h"
#include "renderer/antialiasing/exact_shutter.h"
#include "renderer/backends/grid_meshes.h"
#include "renderer/motion_blur/kinetic_shutter.h"
#include "renderer/output/stats_json.h"
#include "renderer/shadows/kinetic_shadow_tracer.h"
#include "renderer/shadows/lighting.h"
#include "util/check.h"
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
    if (!scene.scene->lights.empty()) {
      m_shadows = make_kinetic_shadow_tracer(scene, config.shadow_tree, config.audit);
      m_lights = CameraSpaceLights(*scene.scene);
    }
  }

  [[nodiscard]] ShadowTracer* shadow_tracer() override { return m_shadows.get(); }
  [[nodiscard]] const WorkProgress* initialisation_progress() const override {
    return &m_init_progress;
  }

  [[nodiscard]] std::string name() const override { return "kinetic"; }

  void plan_frames(std::span<const double> times) override {
    m_plan.assign(times.begin(), times.end());
    m_planned = 0;
    m_ahead_count = m_ahead_next = 0;
  }

  void render(double t, Frame& frame) override {
    if (frame.width != m_config.width || frame.height != m_config.height || frame.pixel_count() == 0)
      frame.resize(m_config.width, m_config.height);
    frame.time = t;
    const bool planned = m_planned < m_plan.size() && m_plan[m_planned] == t;
    if (planned) {
      ++m_planned;
    } else {
      plan_frames({});  // off the plan: what is left of it is dropped
    }
    if (m_grid && planned && m_ahead_next == m_ahead_count) {
      const size_t count = batch_length();
      if (count > 0) render_ahead(t, count);
    }
    if (m_grid && planned && m_ahead_next < m_ahead_count) {
      serve_ahead(frame);
      return;
    }
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

  [[nodiscard]] bool has_exact_antialiasing() const override { return true; }

  void render_antialiased(double t, Frame& frame) override {
    // The centre grid gives the id and depth AOVs (the centre sample); the per-square sets, kept
    // by their own events, give each square's triangles to the exact read-out.
    render(t, frame);
    const auto start = std::chrono::steady_clock::now();
    const uint64_t events_before = m_squares ? m_squares->stats().events.total() : 0;
    if (!m_squares) {
      m_squares = make_square_sets(t);
    } else {
      m_squares->advance_to(t);
    }
    const auto advanced = std::chrono::steady_clock::now();
    // The sets hold meshes by their index in the grid's input; its meshes carry their objects.
    const auto to_ref = [this](const SquareTriangle& e) {
      return TriangleRef{m_squares->input().meshes[e.mesh].id, e.triangle};
    };
    // With lights the centre rays are shaded first, as a lit frame is: frame.lit is the centre
    // hit's light mask (the AOV), and the tracer stands at t for the read-out's shadow rays.
    std::vector<CameraSpaceLight> lights;
    ExactLights exact_lights;
    if (m_shadows) {
      shade_frame_lit(m_scene, m_lights, *m_shadows, frame, m_config.threads);
      lights = m_lights.at(t);
      exact_lights = {&lights, m_shadows.get()};
    }
    exact_frame_colours(
        m_scene, frame, [this](int i, int j) { return m_squares->triangles(i, j); },
        m_config.threads, to_ref, &m_exact_stats, m_shadows ? &exact_lights : nullptr);
    const auto done = std::chrono::steady_clock::now();
    m_square_events_s.push_back(std::chrono::duration<double>(advanced - start).count());
    m_exact_readout_s.push_back(std::chrono::duration<double>(done - advanced).count());
    m_square_events.push_back(m_squares->stats().events.total() - events_before);
  }

  [[nodiscard]] bool has_motion_blur() const override { return true; }

  void render_shutter(const ShutterWindow& window, Frame& frame) override {
    plan_frames({});
    if (m_config.aa == Antialiasing::exact) return render_exact_shutter(window, frame);
    const auto start = std::chrono::steady_clock::now();
    const uint64_t events_before = m_grid ? m_grid->event_count() : 0;
    if (!m_grid)
      m_grid = std::make_unique<FrustumGrid>(
          kinetic_grid_input(m_scene, m_config.width, m_config.height), window.open, m_grid_config);
    if (!m_shutter)
      m_shutter = std::make_unique<KineticShutter>(m_scene, m_config.shutter.order,
                                                   m_config.threads, &m_lights);
    m_shutter->render(*m_grid, window, frame);
    m_events_s.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    m_readout_s.push_back(0);
    m_events.push_back(m_grid->event_count() - events_before);
  }

  /// Exact antialiasing under the shutter (renderer/antialiasing/exact_shutter.h): the ids and
  /// depths are the centre ray's at the frame time, as --aa exact and --shutter each have them.
  void render_exact_shutter(const ShutterWindow& window, Frame& frame) {
    render(window.time, frame);
    if (!m_exact_shutter)
      m_exact_shutter = std::make_unique<ExactShutter>(
          m_scene, ExactShutter::Config{.order = m_config.shutter.order}, m_config.threads,
          [this](double t) { return make_square_sets(t); });
    const PixelSquareSets* before = m_exact_shutter->sets();
    const uint64_t events_before = before ? before->stats().events.total() : 0;
    const ExactShutterStats stats_before = m_exact_shutter->stats();
    m_exact_shutter->render(window, frame);
    const ExactShutterStats& stats = m_exact_shutter->stats();
    // New sets (the first, or built again for a window opening before their time) count their
    // events from zero.
    const bool fresh = before == nullptr || stats.rebuilds != stats_before.rebuilds;
    m_square_events.push_back(m_exact_shutter->sets()->stats().events.total() -
                              (fresh ? 0 : events_before));
    m_square_events_s.push_back(stats.events_s - stats_before.events_s);
    m_exact_readout_s.push_back(stats.readout_s - stats_before.readout_s);
  }

  /// The per-square sets of exact antialiasing at time t, over the grid's input.
  [[nodiscard]] std::unique_ptr<PixelSquareSets> make_square_sets(double t) const {
    PixelSquareSets::Config config;
    config.audit = m_config.audit;
    return std::make_unique<PixelSquareSets>(
        kinetic_grid_input(m_scene, m_config.width, m_config.height), t, config);
  }

  void write_stats(nlohmann::json& stats) const override {
    if (m_shadows) m_shadows->write_stats(stats);
    if (!m_grid) return;
    const PixelSquareSets* squares = m_squares         ? m_squares.get()
                                     : m_exact_shutter ? m_exact_shutter->sets()
                                                       : nullptr;
    if (squares) {
      const ExactPixels::Stats& readout =
          m_exact_shutter ? m_exact_shutter->readout_stats() : m_exact_stats;
      nlohmann::json& aa = stats["antialiasing"];
      aa["mode"] = "exact";
      aa["squares"] = counters_json(squares->stats());
      aa["squares"]["events"] = event_counts_json(squares->stats().events);
      aa["readout"] = {{"pixels", readout.pixels},
                       {"covered_by_one", readout.covered_by_one},
                       {"triangles", readout.triangles},
                       {"pieces", readout.pieces},
                       {"nodes", readout.nodes},
                       {"shadow_rays", readout.shadow_rays},
                       {"shadow_cuts", readout.shadow_cuts}};
      aa["per_frame"] = {{"events_s", m_square_events_s},
                         {"readout_s", m_exact_readout_s},
                         {"events", m_square_events}};
      if (m_exact_shutter) {
        const ExactShutterStats& s = m_exact_shutter->stats();
        aa["shutter"] = {{"order", m_exact_shutter->order()},
                         {"windows", s.windows},
                         {"readouts", s.readouts},
                         {"pieces", s.pieces},
                         {"still_pixels", s.still_pixels},
                         {"changes", s.changes},
                         {"rebuilds", s.rebuilds},
                         {"events_s", s.events_s},
                         {"readout_s", s.readout_s}};
      }
    }
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
    kinetic["frames_batched"] = m_frames_batched;
    kinetic["per_frame"] = {
        {"events_s", m_events_s}, {"readout_s", m_readout_s}, {"events", m_events}};
  }

 private:
  /// A planned frame rendered ahead: its buffers (swapped into the caller's frame when served)
  /// and its share of the batch's time.
  struct AheadFrame {
    std::vector<uint32_t> object, prim;
    std::vector<float> depth;
    double events_s = 0, readout_s = 0;
    uint64_t events = 0;
  };

  /// How many planned frames to render in the next batch, judged by the last frame's events; 0:
  /// none. A batch keeps each band's events in cache over its frames, but its frames' buffers
  /// are written out to memory (streamed), where one frame at a time stays in cache for the
  /// caller: worth it when a frame has many events for its pixels (at least one per 384: on
  /// wavy-sphere at 512x512 one per 256 pays, 0.87 -> 0.82 ms a frame in the median, one per
  /// 512 is a wash, 0.61-0.65 either way; Intel Xeon, 2 MB L2). Long enough for a band's
  /// run of events to reuse what it fetched, short enough that the bands, handed out whole,
  /// share the threads evenly (docs/kinetic_grid.md, "Frames in batches").
  [[nodiscard]] size_t batch_length() const {
    const size_t pixels = size_t(m_config.width) * size_t(m_config.height);
    const uint64_t last = m_events.empty() ? 0 : m_events.back();
    if (last * kPixelsPerBatchedEvent < pixels) return 0;
    const size_t fit =
        kAheadBytes / std::max<size_t>(1, pixels * (2 * sizeof(uint32_t) + sizeof(float)));
    const size_t wanted = size_t(kEventsPerBatch / std::max<uint64_t>(last, 1));
    return std::min({m_plan.size() - (m_planned - 1),
                     std::clamp<size_t>(wanted, 2, kMaxFramesAhead), std::max<size_t>(fit, 1)});
  }

  /// The `count` planned frames from t on, in one FrustumGrid::advance_and_read_out.
  void render_ahead(double t, size_t count) {
    const size_t pixels = size_t(m_config.width) * size_t(m_config.height);
    if (m_ahead.size() < count) m_ahead.resize(count);
    std::vector<BatchFrame> batch(count);
    for (size_t f = 0; f < count; ++f) {
      AheadFrame& a = m_ahead[f];
      a.object.resize(pixels);
      a.prim.resize(pixels);
      a.depth.resize(pixels);
      batch[f] = {
          .t = m_plan[m_planned - 1 + f], .object = a.object, .prim = a.prim, .depth = a.depth};
    }
    KINRAY_CHECK(batch.front().t == t);
    m_grid->advance_and_read_out(batch);
    for (size_t f = 0; f < count; ++f) {
      m_ahead[f].events_s = batch[f].events_s;
      m_ahead[f].readout_s = batch[f].readout_s;
      m_ahead[f].events = batch[f].events;
    }
    m_ahead_count = count;
    m_ahead_next = 0;
  }

  /// The next frame rendered ahead into `frame`: the buffers are swapped, not copied.
  void serve_ahead(Frame& frame) {
    AheadFrame& a = m_ahead[m_ahead_next++];
    frame.object.swap(a.object);
    frame.prim.swap(a.prim);
    frame.depth.swap(a.depth);
    m_events_s.push_back(a.events_s);
    m_readout_s.push_back(a.readout_s);
    m_events.push_back(a.events);
    ++m_frames_batched;
  }

  static constexpr size_t kAheadBytes = size_t(256) << 20;
  static constexpr size_t kMaxFramesAhead = 64;
  static constexpr size_t kPixelsPerBatchedEvent = 384;
  static constexpr uint64_t kEventsPerBatch = uint64_t(1) << 18;

  const CameraSpaceScene& m_scene;
  BackendConfig m_config;
  FrustumGridConfig m_grid_config;
  WorkProgress m_init_progress;  ///< the grid's scan conversion, counted while it is built
  std::unique_ptr<FrustumGrid> m_grid;
  std::unique_ptr<ShadowTracer> m_shadows;  ///< when the scene has lights
  CameraSpaceLights m_lights;               ///< the scene's, for motion blur's shading
  std::unique_ptr<KineticShutter> m_shutter;  ///< motion blur, made by the first render_shutter
  // Exact antialiasing, made by the first render_antialiased: the per-square sets (over the
  // grid's input, which they keep), and their read-out's counters and times.
  std::unique_ptr<PixelSquareSets> m_squares;
  /// Exact antialiasing under the shutter, made by the first render_shutter with --aa exact; it
  /// owns its sets (advanced through the windows' nodes).
  std::unique_ptr<ExactShutter> m_exact_shutter;
  ExactPixels::Stats m_exact_stats;
  std::vector<double> m_square_events_s, m_exact_readout_s;
  std::vector<uint64_t> m_square_events;
  std::vector<double> m_events_s, m_readout_s;
  std::vector<uint64_t> m_events;
  std::vector<double> m_plan;       ///< plan_frames' times
  size_t m_planned = 0;             ///< how many of them render() has been asked for
  std::vector<AheadFrame> m_ahead;  ///< the batch rendered ahead (buffers kept for the next)
  size_t m_ahead_count = 0, m_ahead_next = 0;  ///< frames in the batch, and the next to serve
  uint64_t m_frames_batched = 0;               ///< frames served from batches
};

}  // namespace

std::unique_ptr<Backend> make_kinetic_backend(const CameraSpaceScene& scene, const BackendConfig& config) {
  return std::make_unique<KineticBackend>(scene, config);
}

}  // namespace kinray
