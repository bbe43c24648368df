#pragma once
// Foresight for `kinray render`: once the kinetic backend has rendered its first key interval of
// frames, its cost per frame is known (the grid built, the events of one interval processed), so
// the whole render's time can be projected and set against Embree's, measured on one frame. At a
// low frame rate (few frames per key interval) Embree can be many times faster, and the user is
// told so once, with the flag that changes it.
#include <cstddef>
#include <optional>
#include <string>

namespace kinray {

class RenderJob;

/// What the first frames of a kinetic render and one Embree frame measured, in seconds.
struct ForecastInputs {
  size_t frames_total = 0;       ///< frames the render has
  size_t frames_done = 0;        ///< frames rendered so far (at least 2)
  double load_s = 0;             ///< loading the scene, paid by either backend
  double kinetic_first_s = 0;    ///< kinetic setup and first frame (builds the grid)
  double kinetic_later_s = 0;    ///< kinetic render time of frames 2..frames_done
  double other_per_frame_s = 0;  ///< shading and writing one frame, paid by either backend
  double embree_setup_s = 0;     ///< creating the Embree backend
  double embree_frame_s = 0;     ///< Embree's first frame (with its BVH build: an upper bound)
};

/// The projected time of the whole render with each backend, in seconds.
struct RenderForecast {
  double kinetic_s = 0;
  double embree_s = 0;
};

/// Warn when the kinetic backend is projected to take more than this many times Embree's time...
inline constexpr double kForecastWarnRatio = 5;
/// ...and only for renders projected longer than this (short renders pay no Embree frame).
inline constexpr double kForecastMinKineticS = 10;

/// The kinetic backend's projected time: its first frame, then the mean of its later frames.
[[nodiscard]] double project_kinetic(const ForecastInputs& in);
/// Embree's projected time: its setup, then every frame at the cost of its first.
[[nodiscard]] double project_embree(const ForecastInputs& in);
/// True when the forecast says --backend embree is many times faster.
[[nodiscard]] bool embree_much_faster(const RenderForecast& forecast);
/// The one warning line for `forecast`, for warn(): no "kinray: warning: " prefix, no newline.
[[nodiscard]] std::string forecast_warning(const RenderForecast& forecast);

/// Watches a kinetic render's frame loop and, once its first key interval is done, forecasts
/// the whole render against Embree (timing one Embree frame only when the kinetic projection
/// exceeds kForecastMinKineticS). Forecasts at most once.
class KineticForecast {
 public:
  /// Called after frame `index` of job.frames_to_render() was rendered with the kinetic backend;
  /// returns the forecast when it is due and says Embree is much faster, else nothing.
  [[nodiscard]] std::optional<RenderForecast> frame_done(const RenderJob& job, size_t index);

 private:
  bool m_done = false;
  double m_first_s = -1;      ///< kinetic setup + render after the first frame
  double m_interval_end = 0;  ///< the key time that ends the first key interval
};

}  // namespace kinray
