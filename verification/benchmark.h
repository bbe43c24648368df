#pragma once
// `kinray bench`: renders the same frames with the kinetic backend and with every Embree mode in
// one process, checks while measuring that their ID buffers agree (ties aside), and reports time
// per frame side by side (Embree buildbench style: no warm-up in the figures, the peer in the same
// run, medians over repetitions).
//
// A benchmark is a base configuration plus one-at-a-time sweeps around it: every list flag with
// more than one value (in-betweens, triangle counts, sizes, thread counts) is varied alone while
// the others keep their first value.
#include <functional>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "renderer/job/render_job.h"
#include "verification/bench_support.h"
#include "verification/image_diff.h"

namespace kinray {

/// One Embree configuration of the peer: build mode and ray packet width.
struct EmbreeMode {
  EmbreeBuild build = EmbreeBuild::kRefit;
  int packet = 1;  ///< one of kEmbreePacketWidths
  [[nodiscard]] std::string name() const {
    return embree_build_name(build) + ("/" + std::to_string(packet));
  }
};

struct BenchParams {
  RenderParams base;                      ///< scene, size, threads, --time, sort, model flags
  std::vector<int> inbetweens = {1, 4, 16};
  std::vector<int> triangles;             ///< built-in scenes only: values of the triangles= parameter
  std::vector<std::pair<int, int>> sizes; ///< empty: base size
  std::vector<int> threads;               ///< empty: base threads
  /// Empty: default_embree_modes(), what this machine's Embree offers.
  std::vector<EmbreeMode> embree_modes;
  int repetitions = 3;            ///< medians over this many runs of each measurement
  int reference_frames = 12;      ///< frames per Embree mode, evenly spread over the schedule
};

/// Parses "1,4,16" into positive integers. Throws InputError naming `flag`.
[[nodiscard]] std::vector<int> parse_int_list(const std::string& text, const std::string& flag);
/// The default peers: rebuild/1, rebuild/8, refit/1, refit/4, refit/8, refit/16, less the packet
/// widths this machine's Embree does not trace natively (16 needs AVX-512).
[[nodiscard]] std::vector<EmbreeMode> default_embree_modes(int threads = 0);
/// Parses "rebuild/1,refit/8" into Embree modes. Throws InputError naming --embree-modes.
[[nodiscard]] std::vector<EmbreeMode> parse_embree_modes(const std::string& text);
/// Throws InputError naming the flag at fault.
void validate(const BenchParams& params);

/// What one configuration measured.
struct BenchPoint {
  std::string sweep;               ///< "base", "inbetweens", "triangles", "size" or "threads"
  std::string scene;
  int width = 0, height = 0, threads = 0, inbetweens = 0;
  size_t triangles = 0, frames = 0, key_intervals = 0;

  // The kinetic backend, median over repetitions, per frame unless named otherwise.
  double kinetic_ms_per_frame = 0;   ///< events + read-out (what each extra frame costs)
  double kinetic_init_ms = 0;        ///< one-time initialisation by scan conversion
  double kinetic_events_ms = 0;      ///< event processing, per frame
  double kinetic_readout_ms = 0;     ///< read-out, per frame
  double kinetic_with_init_ms_per_frame = 0;  ///< (init + events + read-out) / frames
  nlohmann::json kinetic_stats;      ///< the backend's own --stats of the first repetition

  struct Peer {
    std::string mode;
    double ms_per_frame = 0;         ///< median over frames and repetitions, warm-up excluded
    size_t frames_measured = 0;
    size_t mismatch_real = 0, mismatch_tie = 0;
    /// Adds a comparison with the kinetic frame to the mismatch counts; returns its pixel count.
    size_t count(const FrameDiff& diff);
  };
  std::vector<Peer> embree;
  double embree_best_ms_per_frame = 0;
  std::string embree_best_mode;
  double speedup_vs_best_embree = 0;  ///< embree_best_ms_per_frame / kinetic_ms_per_frame
  double embree_build_and_trace_ms = 0;  ///< one Embree rebuild plus trace, to set beside init
  size_t pixels_compared = 0, mismatch_real = 0, mismatch_tie = 0;
  // --backend auto over the same frames (renderer/auto_backend.h), its whole wall time.
  double auto_ms_per_frame = 0;    ///< median over repetitions, measuring included
  std::string auto_summary;        ///< what it rendered with (first repetition)
  /// The faster of the kinetic backend (initialisation included) and Embree's best mode (its
  /// first build included), per frame: what auto is set against.
  double faster_ms_per_frame = 0;
  /// Kinetic events (all kinds) per keyframe interval of the measured frames.
  [[nodiscard]] double events_per_key_interval() const;
};

struct BenchReport {
  std::vector<BenchPoint> points;
  std::string base_scene;  ///< the scene of the base configuration
  /// Event processing cost on one core at the base configuration (time_s.events / events.total,
  /// median over repetitions): from a measured one-thread point, else from its own kinetic runs.
  std::optional<double> ns_per_event_one_thread;
  [[nodiscard]] nlohmann::json to_json() const;
  /// One row per (configuration, backend mode).
  [[nodiscard]] std::string to_csv() const;
  /// In-betweens sweep: the smallest measured in-between count from which the kinetic backend
  /// is at least as fast per frame as the best Embree mode (linear interpolation in log2 K).
  [[nodiscard]] std::optional<double> break_even_inbetweens() const;
  /// Writes one PNG chart per sweep into `folder` (created if needed); returns the paths.
  std::vector<std::string> write_charts(const std::string& folder) const;
  /// A readable table.
  void print(std::ostream& out) const;
};

/// One run of a backend over frame times: its --stats, the frames at the sampled indices and the
/// wall time from creating the backend to the last frame.
struct BackendRun {
  nlohmann::json stats;
  std::vector<Frame> sampled_frames;
  double wall_ms = 0;
};
/// Renders `times` of `job` with the backend `make` creates, keeping the frames at the indices
/// `sampled` (increasing).
[[nodiscard]] BackendRun run_backend(RenderJob& job,
                                     const std::function<std::unique_ptr<Backend>()>& make,
                                     std::span<const double> times,
                                     std::span<const size_t> sampled);
/// An Embree backend of `job`'s scene and flags in `mode`.
[[nodiscard]] std::unique_ptr<Backend> make_embree_backend(const RenderJob& job,
                                                           const EmbreeMode& mode);
/// Measures one configuration on a loaded job: the kinetic backend over `times` (made with
/// `inbetweens` per keyframe interval) and every Embree mode of `bench` on frames spread over
/// them, checked against each other. The point's sweep is "base".
[[nodiscard]] BenchPoint measure_frames(const BenchParams& bench, RenderJob& job,
                                        const std::vector<double>& times, int inbetweens);

/// Runs every configuration; `progress` gets a line before each one.
[[nodiscard]] BenchReport run_benchmark(const BenchParams& params,
                                        const std::function<void(const std::string&)>& progress = {});

}  // namespace kinray
