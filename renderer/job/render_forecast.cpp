#include "renderer/job/render_forecast.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>

#include "renderer/backends/backend.h"
#include "renderer/frame.h"
#include "renderer/job/render_job.h"
#include "util/input_error.h"

namespace kinray {

double project_kinetic(const ForecastInputs& in) {
  const double n = double(in.frames_total);
  const double later = in.frames_done > 1 ? in.kinetic_later_s / double(in.frames_done - 1) : 0;
  return in.load_s + in.kinetic_first_s + later * std::max(n - 1, 0.0) + in.other_per_frame_s * n;
}

double project_embree(const ForecastInputs& in) {
  const double n = double(in.frames_total);
  return in.load_s + in.embree_setup_s + (in.embree_frame_s + in.other_per_frame_s) * n;
}

bool embree_much_faster(const RenderForecast& forecast) {
  return forecast.kinetic_s > kForecastMinKineticS &&
         forecast.kinetic_s > kForecastWarnRatio * forecast.embree_s;
}

std::string forecast_warning(const RenderForecast& forecast) {
  char text[400];
  std::snprintf(text, sizeof text,
                "the kinetic backend will take about %.0f s for this render, "
                "Embree about %.1f s; --backend embree is faster at this frame rate (kinetic wins "
                "with many frames per keyframe interval: --inbetweens)",
                forecast.kinetic_s, forecast.embree_s);
  return text;
}

std::optional<RenderForecast> KineticForecast::frame_done(const RenderJob& job, size_t index) {
  // Motion blur renders shutter windows, which one plain Embree frame does not measure.
  if (m_done || !job.shutter_windows().empty()) return std::nullopt;
  const RenderTimings& timings = job.timings();
  const std::vector<size_t>& rendered = job.frames_to_render();
  const std::vector<double>& times = job.frame_times();
  if (index == rendered.front()) {
    m_first_s = timings.setup + timings.render;
    // The key interval holding the first frame ends at the first key time after it.
    const std::vector<double> keys = job.scene().key_times();
    const auto next = std::upper_bound(keys.begin(), keys.end(), times.at(index));
    m_interval_end = next == keys.end() ? std::numeric_limits<double>::infinity() : *next;
    return std::nullopt;
  }
  const size_t done = timings.frames + 1;  // this frame is rendered, not yet counted
  if (times.at(index) < m_interval_end || done >= rendered.size()) {
    if (done >= rendered.size()) m_done = true;
    return std::nullopt;
  }
  m_done = true;
  ForecastInputs in;
  in.frames_total = rendered.size();
  in.frames_done = done;
  in.load_s = timings.load;
  in.kinetic_first_s = m_first_s;
  in.kinetic_later_s = timings.setup + timings.render - m_first_s;
  in.other_per_frame_s = (timings.shade + timings.write) / double(done);
  RenderForecast forecast{.kinetic_s = project_kinetic(in)};
  if (forecast.kinetic_s <= kForecastMinKineticS) return std::nullopt;
  // Embree is timed on this very frame, outside the job (its timings stay the kinetic render's).
  using Clock = std::chrono::steady_clock;
  const Clock::time_point start = Clock::now();
  std::unique_ptr<Backend> embree;
  try {
    embree = make_backend("embree", job.camera_space(), backend_config(job.params()));
  } catch (const InputError&) {
    return std::nullopt;  // flags Embree does not take: there is no Embree render to suggest
  }
  const Clock::time_point built = Clock::now();
  Frame frame;
  frame.resize(job.params().width, job.params().height);
  embree->render(times.at(index), frame);
  in.embree_setup_s = std::chrono::duration<double>(built - start).count();
  in.embree_frame_s = std::chrono::duration<double>(Clock::now() - built).count();
  forecast.embree_s = project_embree(in);
  if (!embree_much_faster(forecast)) return std::nullopt;
  return forecast;
}

}  // namespace kinray
