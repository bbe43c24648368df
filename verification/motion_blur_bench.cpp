#include "verification/motion_blur_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "util/input_error.h"
#include "verification/bench_support.h"
#include "verification/coincident_fronts.h"
#include "verification/image_diff.h"

namespace kinray {
namespace {

/// The backend's --stats "shutter" seconds (zeros when it has none).
struct ShutterSeconds {
  double events = 0, integrate = 0, readout = 0;
};
ShutterSeconds shutter_seconds(const Backend& backend) {
  nlohmann::json stats = nlohmann::json::object();
  backend.write_stats(stats);
  if (!stats.contains("shutter")) return {};
  const nlohmann::json& s = stats["shutter"];
  return {s.value("events_s", 0.0), s.value("integrate_s", 0.0), s.value("readout_s", 0.0)};
}

}  // namespace

nlohmann::json MotionBlurResult::to_json() const {
  nlohmann::json embree_points = nlohmann::json::array();
  for (const MotionBlurPoint& p : embree) embree_points.push_back(p.to_json());
  return {{"scene", scene},
          {"size", {{"width", width}, {"height", height}}},
          {"triangles", triangles},
          {"lights", lights},
          {"frames", frames},
          {"shutter", shutter},
          {"reference_samples", reference_samples},
          {"kinetic",
           {{"ms_per_frame", kinetic.ms_per_frame},
            {"rmse", kinetic.rmse},
            {"max_error", kinetic.max_error},
            {"init_ms", kinetic_init_ms},
            {"events_ms", kinetic_events_ms},
            {"integrate_ms", kinetic_integrate_ms},
            {"readout_ms", kinetic_readout_ms},
            {"order", order},
            {"rmse_with_ties", kinetic_rmse_with_ties}}},
          {"tie_pixels", tie_pixels},
          {"embree", embree_points},
          {"meets_targets", meets_targets()}};
}

bool MotionBlurResult::meets_targets() const {
  bool ok = true;
  for (const MotionBlurPoint& p : embree) {
    if (p.samples == 256) ok = ok && kinetic.rmse <= p.rmse;
    if (p.samples == 64) ok = ok && kinetic.ms_per_frame * (lights > 0 ? 5 : 10) <= p.ms_per_frame;
  }
  return ok;
}

MotionBlurResult run_motion_blur_bench(const RenderParams& params,
                                       const MotionBlurBenchParams& bench,
                                       const std::function<void(const std::string&)>& log) {
  if (!params.shutter.enabled())
    throw InputError("--shutter", "the motion blur benchmark needs S > 0");
  if (bench.reference_samples < 1 || bench.reference_samples > kMaxShutterSamples)
    throw InputError("--reference-samples", "must lie in 1.." + std::to_string(kMaxShutterSamples));
  for (int n : bench.samples)
    if (n < 1 || n > kMaxShutterSamples)
      throw InputError("--blur-samples",
                       "each must lie in 1.." + std::to_string(kMaxShutterSamples));
  RenderJob job(params);
  MotionBlurResult result;
  result.scene = params.scene;
  result.width = params.width;
  result.height = params.height;
  result.shutter = params.shutter.shutter;
  result.reference_samples = bench.reference_samples;
  result.frames = job.frame_times().size();
  result.triangles = job.scene().triangle_count();
  result.lights = job.scene().lights.size();
  char line[512];
  TieMasks ties;  // per frame, found from the kinetic frames

  // The reference frames first, kept for every method.
  std::vector<Frame> reference(job.frame_times().size());
  {
    BackendConfig config = backend_config(params);
    config.shutter.samples = bench.reference_samples;
    const double start = now_ms();
    std::unique_ptr<Backend> embree = make_backend("embree", job.camera_space(), config);
    for (size_t index = 0; index < reference.size(); ++index)
      job.render_frame(*embree, index, reference[index]);
    std::snprintf(line, sizeof line, "%s: reference, %d samples per pixel, %zu frames: %.1f s",
                  params.scene.c_str(), bench.reference_samples, reference.size(),
                  (now_ms() - start) / 1000);
    log(line);
  }
  {
    std::unique_ptr<Backend> kinetic = job.make_backend("kinetic");
    double first_ms = 0;
    ShutterSeconds split;
    std::vector<Frame> frames(reference.size());
    result.kinetic = measure_quality(
        job,
        [&](size_t index, Frame& frame) {
          job.render_frame(*kinetic, index, frame);
          frames[index] = frame;
        },
        reference, 0, &first_ms, [&] { split = shutter_seconds(*kinetic); });
    // Coincident surfaces flicker in every renderer, so their pixels are ties: every method's
    // error is measured without them (coincident_fronts.h), the kinetic error with them kept too.
    result.kinetic_rmse_with_ties = result.kinetic.rmse;
    for (size_t index = 0; index < frames.size(); ++index) {
      ties.push_back(coincident_fronts(job.camera_space(), job.shutter_windows()[index],
                                       frames[index], reference[index]));
      result.tie_pixels += size_t(std::count(ties.back().begin(), ties.back().end(), uint8_t(1)));
    }
    measure_error(frames, reference, ties, result.kinetic);
    if (job.frame_times().size() > 1) {
      // The frames after the first: the whole run's seconds less the first frame's.
      const ShutterSeconds all = shutter_seconds(*kinetic);
      const double timed = double(job.frame_times().size() - 1);
      split = {(all.events - split.events) / timed, (all.integrate - split.integrate) / timed,
               (all.readout - split.readout) / timed};
    }
    result.kinetic_events_ms = split.events * 1000;
    result.kinetic_integrate_ms = split.integrate * 1000;
    result.kinetic_readout_ms = split.readout * 1000;
    result.kinetic_init_ms = std::max(0.0, first_ms - result.kinetic.ms_per_frame);
    result.order = params.shutter.order > 0 ? params.shutter.order : kDefaultShutterOrder;
    std::snprintf(line, sizeof line,
                  "%s: kinetic: %.2f ms per frame (init %.0f ms; mean events %.0f ms, integration "
                  "%.0f ms, read-out %.0f ms), rmse %.3g, max %.3g",
                  params.scene.c_str(), result.kinetic.ms_per_frame, result.kinetic_init_ms,
                  result.kinetic_events_ms, result.kinetic_integrate_ms, result.kinetic_readout_ms,
                  result.kinetic.rmse, result.kinetic.max_error);
    log(line);
    if (result.tie_pixels > 0) {
      std::snprintf(line, sizeof line,
                    "%s: %zu pixels of coincident surfaces set aside as ties in every error "
                    "(the kinetic rmse with them: %.3g)",
                    params.scene.c_str(), result.tie_pixels, result.kinetic_rmse_with_ties);
      log(line);
    }
  }
  for (int n : bench.samples) {
    BackendConfig config = backend_config(params);
    config.shutter.samples = n;
    std::unique_ptr<Backend> embree = make_backend("embree", job.camera_space(), config);
    result.embree.push_back(measure_quality(
        job, [&](size_t index, Frame& frame) { job.render_frame(*embree, index, frame); },
        reference, n, nullptr, {}, ties));
    const MotionBlurPoint& p = result.embree.back();
    std::snprintf(line, sizeof line,
                  "%s: embree %4d samples: %.2f ms per frame, rmse %.3g, max %.3g",
                  params.scene.c_str(), n, p.ms_per_frame, p.rmse, p.max_error);
    log(line);
  }
  return result;
}

void write_motion_blur_chart(const std::vector<MotionBlurResult>& results,
                             const std::string& path) {
  std::vector<QualityCurve> curves;
  for (const MotionBlurResult& r : results) curves.push_back({r.scene, r.kinetic, r.embree});
  write_quality_chart("Motion blur: error against time per frame", curves, path);
}

}  // namespace kinray
