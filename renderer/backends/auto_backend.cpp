#include "renderer/backends/auto_backend.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "renderer/backends/embree_backend.h"
#include "renderer/backends/kinetic_backend.h"
#include "renderer/job/frame_schedule.h"
#include "renderer/job/memory_estimate.h"
#include "util/stopwatch.h"

namespace kinray {
namespace {

using Clock = std::chrono::steady_clock;

class AutoBackend final : public Backend {
 public:
  AutoBackend(const CameraSpaceScene& scene, const BackendConfig& config)
      : m_scene(scene), m_config(config), m_keys(scene.scene->key_times()) {
    BackendConfig embree = config;
    embree.embree_build = EmbreeBuild::kRefit;
    // The widest native packet up to 8: 16-wide packets (AVX-512) measured no faster than 8 on
    // the built-in scenes, and slower on some machines.
    const std::vector<int> widths = embree_packet_widths(config.threads);
    for (int width : widths)
      if (width <= 8) embree.embree_packet = width;
    m_embree_packet = embree.embree_packet;
    m_embree = make_embree_backend(scene, embree);
  }

  [[nodiscard]] std::string name() const override { return "auto"; }

  void plan_frames(std::span<const double> times) override {
    m_plan.assign(times.begin(), times.end());
    m_embree->plan_frames(times);
    if (m_kinetic) m_kinetic->plan_frames(times);
  }

  void render(double t, Frame& frame) override {
    const Clock::time_point start = Clock::now();
    switch (m_phase) {
      case Phase::measure_embree:
        m_embree->render(t, frame);
        ++m_frames_embree;
        (m_frames_embree == 1 ? m_embree_first_s : m_embree_frame_s) = seconds_since(start);
        if (m_frames_embree == 2) decide_on_trial(t);
        return;
      case Phase::embree:
        m_embree->render(t, frame);
        ++m_frames_embree;
        return;
      case Phase::kinetic_trial:
        render_trial(t, frame, start);
        return;
      case Phase::kinetic:
        m_kinetic->render(t, frame);
        ++m_frames_kinetic;
        check_grid(t, seconds_since(start));
        return;
    }
  }

  void write_stats(nlohmann::json& stats) const override {
    m_embree->write_stats(stats);
    if (m_kinetic) m_kinetic->write_stats(stats);
    stats["auto"] = {{"summary", summary()},
                     {"frames", {{"embree", m_frames_embree}, {"kinetic", m_frames_kinetic}}},
                     {"embree_packet", m_embree_packet},
                     {"embree_first_frame_s", m_embree_first_s},
                     {"embree_frame_s", m_embree_frame_s},
                     {"kinetic_tried", m_kinetic != nullptr},
                     {"kinetic_first_frame_s", m_kinetic_first_s},
                     {"kinetic_s_per_shot_second", m_kinetic_rate},
                     {"decisions", m_decisions}};
  }

  [[nodiscard]] ShadowTracer* shadow_tracer() override {
    return uses_kinetic() ? m_kinetic->shadow_tracer() : m_embree->shadow_tracer();
  }

 private:
  enum class Phase { measure_embree, embree, kinetic_trial, kinetic };

  [[nodiscard]] bool uses_kinetic() const {
    return m_phase == Phase::kinetic || m_phase == Phase::kinetic_trial;
  }

  /// The planned frames after time t, and the last planned time.
  [[nodiscard]] size_t frames_after(double t) const {
    return size_t(m_plan.end() - std::upper_bound(m_plan.begin(), m_plan.end(), t));
  }

  void decide(Phase phase, const std::string& why) {
    m_phase = phase;
    m_decisions.push_back(why);
  }

  /// After Embree's second frame at t: is the rest of the shot long enough to try the grid?
  /// Frames per keyframe interval over the plan: its frames over the key intervals it spans.
  [[nodiscard]] double frames_per_interval() const {
    return frames_per_key_interval(m_plan, m_keys);
  }

  void decide_on_trial(double t) {
    const double embree_left = m_embree_frame_s * double(frames_after(t));
    char text[200];
    if (frames_per_interval() < kMinFramesPerInterval) {
      std::snprintf(text, sizeof text,
                    "Embree: %.1f frames per keyframe interval, fewer than %.0f (the grid's "
                    "break-even is 6 to over 60 on the scenes measured)",
                    frames_per_interval(), kMinFramesPerInterval);
      decide(Phase::embree, text);
      return;
    }
    const std::optional<double> available = available_memory_bytes();
    if (available &&
        estimate_render_memory(size_of(m_scene), m_config.width, m_config.height, "kinetic")
                .total() > *available) {
      decide(Phase::embree, "Embree: the kinetic grid would not fit in memory");
      return;
    }
    if (embree_left < kInitInEmbreeBuilds * m_embree_first_s) {
      std::snprintf(text, sizeof text,
                    "Embree: the %zu frames left cost %.3f s with it, less than %.0f first Embree "
                    "frames (%.3f s each), which the grid's initialisation takes",
                    frames_after(t), embree_left, kInitInEmbreeBuilds, m_embree_first_s);
      decide(Phase::embree, text);
      return;
    }
    std::snprintf(text, sizeof text,
                  "kinetic tried: the %zu frames left cost %.3f s with Embree, more than %.0f "
                  "first Embree frames",
                  frames_after(t), embree_left, kInitInEmbreeBuilds);
    decide(Phase::kinetic_trial, text);
  }

  /// A frame of the grid's trial: the first builds it; the first frame at or after the end of
  /// that frame's keyframe interval decides between the grid and Embree for the rest.
  void render_trial(double t, Frame& frame, Clock::time_point start) {
    if (!m_kinetic) {
      m_kinetic = make_kinetic_backend(m_scene, m_config);
      m_trial_start = t;
      const auto next_key = std::upper_bound(m_keys.begin(), m_keys.end(), t);
      m_trial_end = next_key == m_keys.end() ? m_plan.back() : std::min(*next_key, m_plan.back());
      // The grid renders frames ahead in batches: planned up to the trial's end only, so that
      // the trial's time is its own interval's.
      const auto from = std::lower_bound(m_plan.begin(), m_plan.end(), t);
      const auto to = std::upper_bound(from, m_plan.end(), m_trial_end);
      m_kinetic->plan_frames(std::span<const double>(m_plan).subspan(
          size_t(from - m_plan.begin()), size_t(to - from)));
      m_kinetic->render(t, frame);
      ++m_frames_kinetic;
      m_kinetic_first_s = seconds_since(start);
      if (!(m_trial_end > t)) decide(Phase::kinetic, "kinetic: no frame after the grid's first");
      return;
    }
    m_kinetic->render(t, frame);
    ++m_frames_kinetic;
    m_trial_s += seconds_since(start);
    if (t < m_trial_end) return;
    const auto rest = std::upper_bound(m_plan.begin(), m_plan.end(), t);
    m_kinetic->plan_frames(std::span<const double>(m_plan).subspan(size_t(rest - m_plan.begin())));
    m_kinetic_rate = m_trial_s / (t - m_trial_start);
    const double kinetic_left = m_kinetic_rate * (m_plan.back() - t);
    const double embree_left = m_embree_frame_s * double(frames_after(t));
    char text[200];
    std::snprintf(text, sizeof text,
                  "%s: after one keyframe interval the rest of the shot costs %.3f s with the "
                  "grid, %.3f s with Embree",
                  kinetic_left <= embree_left ? "kinetic" : "Embree", kinetic_left, embree_left);
    decide(kinetic_left <= embree_left ? Phase::kinetic : Phase::embree, text);
    if (m_phase == Phase::kinetic) start_check(t);
  }

  /// The check of the grid's choice starts over at t: the keyframe interval after t's.
  void start_check(double t) {
    const auto next_key = std::upper_bound(m_keys.begin(), m_keys.end(), t);
    m_check_end = next_key == m_keys.end() ? m_plan.back() : *next_key;
    m_check_s = 0;
    m_check_frames = 0;
  }

  /// A frame of the grid at t took `seconds`: at the last frame of a keyframe interval, did the
  /// interval cost the grid clearly more than Embree's frames would have?
  void check_grid(double t, double seconds) {
    m_check_s += seconds;
    ++m_check_frames;
    const auto next = std::upper_bound(m_plan.begin(), m_plan.end(), t);
    if (next == m_plan.end()) return;  // the shot's last frame: nothing to hand on
    if (*next <= m_check_end) return;  // the interval goes on
    m_lost_in_a_row =
        grid_lost_interval(m_check_s, m_check_frames, m_embree_frame_s) ? m_lost_in_a_row + 1 : 0;
    if (m_lost_in_a_row >= kGridLostIntervals) {
      char text[240];
      std::snprintf(text, sizeof text,
                    "Embree: %d keyframe intervals in a row cost the grid more than %.1f times "
                    "Embree's frames (the last %.1f ms for %zu frames, Embree's frame %.3f ms)",
                    kGridLostIntervals, kGridCheckMargin, 1e3 * m_check_s, m_check_frames,
                    1e3 * m_embree_frame_s);
      decide(Phase::embree, text);
      return;
    }
    start_check(*next);
  }

  [[nodiscard]] std::string summary() const {
    std::string line = std::to_string(m_frames_embree) + " frame" +
                       (m_frames_embree == 1 ? "" : "s") + " with Embree, " +
                       std::to_string(m_frames_kinetic) + " with the kinetic grid";
    if (!m_decisions.empty()) line += "; " + m_decisions.back();
    return line;
  }

  const CameraSpaceScene& m_scene;
  BackendConfig m_config;
  std::vector<double> m_keys;  ///< the scene's key times
  std::vector<double> m_plan;  ///< plan_frames' times
  std::unique_ptr<Backend> m_embree, m_kinetic;
  int m_embree_packet = 1;
  Phase m_phase = Phase::measure_embree;
  size_t m_frames_embree = 0, m_frames_kinetic = 0;
  double m_embree_first_s = 0, m_embree_frame_s = 0;
  double m_kinetic_first_s = 0, m_trial_s = 0, m_kinetic_rate = 0;
  double m_trial_start = 0, m_trial_end = 0;
  /// The check of the grid's choice (check_grid): the current keyframe interval's end, the grid's
  /// time and frames in it so far.
  double m_check_end = 0, m_check_s = 0;
  size_t m_check_frames = 0;
  int m_lost_in_a_row = 0;  ///< keyframe intervals just checked that the grid lost
  std::vector<std::string> m_decisions;
};

}  // namespace

std::unique_ptr<Backend> make_auto_backend(const CameraSpaceScene& scene,
                                           const BackendConfig& config) {
  const BackendConfig defaults;
  // Motion blur with antialiasing samples is the sampling peer's (x, y, t) sampling: embree.
  if ((config.shutter.enabled() && config.aa_samples == 1) || config.sort != defaults.sort ||
      config.audit || config.shadow_tree != defaults.shadow_tree ||
      config.aa == Antialiasing::exact)
    return make_kinetic_backend(scene, config);
  if (config.embree_packet != defaults.embree_packet ||
      config.embree_build != defaults.embree_build || config.aa_samples > 1)
    return make_embree_backend(scene, config);
  return std::make_unique<AutoBackend>(scene, config);
}

}  // namespace kinray
