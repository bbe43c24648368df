#pragma once
// Which frame times to render: --frames N, --fps F or --inbetweens K over the shot, optionally
// restricted by --time A:B. The schedule depends only on the shot and its keyframe grid, never on
// the backend, so every backend renders the same times.
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace kinray {

inline constexpr int kDefaultFrameCount = 24;
inline constexpr size_t kMaxFrameCount = 1'000'000;

/// One field per flag; at most one of frames, fps and inbetweens may be set (none: 24 frames).
struct FrameScheduleParams {
  std::optional<int> frames;  ///< --frames N: N frames evenly over the shot, both ends included
  std::optional<double> fps;  ///< --fps F: every multiple of 1/F inside the shot
  std::optional<int>
      inbetweens;  ///< --inbetweens K: K frames per keyframe interval, plus the last key
  std::optional<std::pair<double, double>> time;  ///< --time A:B: restricts the shot to [A, B]
};

/// Parses "A:B" (two finite numbers, A < B). Throws InputError naming --time for text that is
/// not A:B, OptionError naming the field time for a bad range.
[[nodiscard]] std::pair<double, double> parse_time_range(const std::string& text);

/// Throws OptionError naming the field when a value is out of range (N >= 1, F > 0, K >= 1,
/// A < B, all finite), InputError when more than one of --frames, --fps, --inbetweens is given.
void validate(const FrameScheduleParams& params);

/// Frame times, increasing, for a shot whose keyframe grid is `key_times` (sorted, first and last
/// = the shot's ends, as Scene::key_times()). --time must lie inside the shot; the grid is cut to
/// [A, B] (keys strictly inside, plus A and B). Throws OptionError naming the field at fault,
/// including when fps finds no frame or a schedule exceeds kMaxFrameCount frames.
[[nodiscard]] std::vector<double> frame_times(std::span<const double> key_times,
                                              const FrameScheduleParams& params);

/// The keyframe intervals that `frames` (increasing) span on the grid `key_times`: those that
/// hold a frame or lie between two (at least 1).
[[nodiscard]] size_t key_intervals_spanned(std::span<const double> frames,
                                           std::span<const double> key_times);
/// Frames per keyframe interval over a schedule: the kinetic grid processes every event of the
/// intervals it spans, Embree only renders the frames.
[[nodiscard]] inline double frames_per_key_interval(std::span<const double> frames,
                                                    std::span<const double> key_times) {
  return double(frames.size()) / double(key_intervals_spanned(frames, key_times));
}

}  // namespace kinray
