#include "verification/antialiasing_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "renderer/antialiasing/pixel_samples.h"
#include "util/input_error.h"
#include "verification/antialiasing_diff.h"
#include "verification/bench_support.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

/// The kinetic backend's square-set events per frame from its --stats (empty when it has none).
std::vector<double> square_events(const Backend& backend) {
  nlohmann::json stats = nlohmann::json::object();
  backend.write_stats(stats);
  const nlohmann::json* aa = stats.contains("antialiasing") ? &stats["antialiasing"] : nullptr;
  if (aa == nullptr || !aa->contains("per_frame")) return {};
  return (*aa)["per_frame"].value("events", std::vector<double>{});
}

}  // namespace

double keyframe_intervals(const std::vector<double>& keys, double a, double b) {
  double spanned = 0;
  for (size_t k = 0; k + 1 < keys.size(); ++k) {
    const double overlap = std::min(b, keys[k + 1]) - std::max(a, keys[k]);
    if (overlap > 0) spanned += overlap / (keys[k + 1] - keys[k]);
  }
  return spanned;
}

nlohmann::json AntialiasingResult::to_json() const {
  nlohmann::json embree_points = nlohmann::json::array();
  for (const AntialiasingPoint& p : embree) embree_points.push_back(p.to_json());
  nlohmann::json json = {{"scene", scene},
                         {"size", {{"width", width}, {"height", height}}},
                         {"triangles", triangles},
                         {"lights", lights},
                         {"frames", frames},
                         {"reference_samples", reference_samples},
                         {"kinetic",
                          {{"ms_per_frame", kinetic.ms_per_frame},
                           {"rmse", kinetic.rmse},
                           {"max_error", kinetic.max_error},
                           {"events_per_interval", events_per_interval},
                           {"init_ms", kinetic_init_ms}}},
                         {"embree", embree_points}};
  if (shutter > 0) json["shutter"] = shutter;
  return json;
}

AntialiasingResult run_antialiasing_bench(const RenderParams& params,
                                          const AntialiasingBenchParams& bench,
                                          const std::function<void(const std::string&)>& log) {
  if (params.aa != Antialiasing::exact)
    throw InputError("--aa", "the antialiasing benchmark measures --aa exact");
  check_reference_samples(bench.reference_samples);
  for (int n : bench.samples)
    if (!is_aa_sample_count(n))
      throw InputError("--aa-sample-counts", "each must be a square in 1.." +
                                                 std::to_string(kMaxAaSamples) + ", got " +
                                                 std::to_string(n));
  RenderJob job(params);
  AntialiasingResult result;
  result.scene = params.scene;
  result.width = params.width;
  result.height = params.height;
  result.reference_samples = bench.reference_samples;
  result.shutter = params.shutter.shutter;
  result.frames = job.frame_times().size();
  result.triangles = job.scene().triangle_count();
  result.lights = job.scene().lights.size();
  const std::vector<double>& times = job.frame_times();
  char line[512];

  // Embree at `samples` per pixel; the job's render_frame would ask it for --aa exact.
  const auto embree_at = [&](int samples) {
    BackendConfig config = backend_config(params);
    config.aa = Antialiasing::none;
    config.aa_samples = samples;
    return make_backend("embree", job.camera_space(), config);
  };
  // Under the shutter the job renders each frame's window (samples in (x, y, t)); else the
  // frame time's supersampled frame.
  const bool blurred = params.shutter.enabled();
  const auto render_embree = [&](Backend& embree, size_t index, Frame& frame) {
    if (blurred)
      job.render_frame(embree, index, frame);
    else
      embree.render_supersampled(times[index], frame);
  };
  // The reference frames first, kept for every method.
  std::vector<Frame> reference(times.size());
  {
    const double start = now_ms();
    std::unique_ptr<Backend> embree = embree_at(bench.reference_samples);
    for (size_t index = 0; index < reference.size(); ++index)
      render_embree(*embree, index, reference[index]);
    std::snprintf(line, sizeof line, "%s: reference, %d samples per pixel, %zu frames: %.1f s",
                  params.scene.c_str(), bench.reference_samples, reference.size(),
                  (now_ms() - start) / 1000);
    log(line);
  }
  {
    std::unique_ptr<Backend> kinetic = job.make_backend("kinetic");
    double first_ms = 0;
    result.kinetic = measure_quality(
        job, [&](size_t index, Frame& frame) { job.render_frame(*kinetic, index, frame); },
        reference, 0, &first_ms);
    result.kinetic_init_ms = std::max(0.0, first_ms - result.kinetic.ms_per_frame);
    // The first frame builds the sets; the events of the later ones advance them from the first
    // frame's time to the last's.
    const std::vector<double> events = square_events(*kinetic);
    double later = 0;
    for (size_t f = 1; f < events.size(); ++f) later += events[f];
    const double intervals =
        keyframe_intervals(job.scene().key_times(), times.front(), times.back());
    result.events_per_interval = intervals > 0 ? later / intervals : 0;
    std::snprintf(line, sizeof line,
                  "%s: kinetic exact%s: %.2f ms per frame (init %.0f ms), %.0f square events per "
                  "keyframe interval, rmse %.3g, max %.3g",
                  params.scene.c_str(), blurred ? " (space-time)" : "", result.kinetic.ms_per_frame,
                  result.kinetic_init_ms, result.events_per_interval, result.kinetic.rmse,
                  result.kinetic.max_error);
    log(line);
  }
  for (int n : bench.samples) {
    std::unique_ptr<Backend> embree = embree_at(n);
    result.embree.push_back(measure_quality(
        job, [&](size_t index, Frame& frame) { render_embree(*embree, index, frame); }, reference,
        n, nullptr));
    const AntialiasingPoint& p = result.embree.back();
    std::snprintf(line, sizeof line,
                  "%s: embree %4d samples: %.2f ms per frame, rmse %.3g, max %.3g",
                  params.scene.c_str(), n, p.ms_per_frame, p.rmse, p.max_error);
    log(line);
  }
  return result;
}

}  // namespace kinray
