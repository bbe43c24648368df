#pragma once
// `kinray diff --aa exact`: an exactly antialiased pixel is the box-filtered mean over its square,
// which no single ray gives, so the tested backend's frames are compared by colour with Embree's
// stratified supersampling at very many samples per pixel (embree_supersampling.h), frame by
// frame, within a stated tolerance -- as `diff --shutter` does for motion blur. Under the shutter
// (`--aa exact --shutter S`) the reference samples the pixel's square and its window together.
#include <string>

#include "renderer/job/render_job.h"
#include "verification/color_diff.h"

namespace kinray {

/// Antialiasing samples per pixel of the reference frame unless --reference-samples says otherwise.
inline constexpr int kAntialiasingReferenceSamples = 4096;

/// What `kinray diff --aa exact` accepts per frame (linear RGB). The exact frame differs from the
/// box filter only by float rounding, so what is left is the reference's sampling error: an edge
/// of contrast c <= 1 through a pixel crosses m of its N = m x m strata, each off by at most 1/N
/// of the pixel, so the pixel errs by at most c / m (a few edges: a few c / m) and typically by
/// c / m^1.5 (the strata's errors have random signs). Hence max 3 / m and RMSE 1 / m^1.5, which
/// holds even when every pixel holds an edge: at the default 4096 samples 0.047 and 1.95e-3, the
/// bounds of `diff --shutter`. Measured on wavy-sphere:triangles=2000 at 32x24: RMSE 2.4e-5 at
/// 4096 samples, 6.6e-5 at 1024 -- falling as the reference's noise does.
struct AntialiasingTolerance : ColorTolerance {
  /// The bounds above for a reference of `samples` (a square) per pixel.
  [[nodiscard]] static AntialiasingTolerance for_samples(int samples);
};

struct AntialiasingDiffOptions {
  int reference_samples = kAntialiasingReferenceSamples;  ///< --reference-samples (a square)
  std::string report;  ///< --report DIR: tested, reference and error images per frame
  std::string json;    ///< --json FILE
};

/// Throws InputError naming --reference-samples unless `samples` is a square in 1..kMaxAaSamples.
void check_reference_samples(int samples);

/// Renders every frame with params.backend (--aa exact, or --aa-samples N: the sampling peer) and
/// with the Embree reference at
/// options.reference_samples, prints RMSE and max error per frame and a last line with the worst,
/// and throws std::runtime_error when a frame is outside AntialiasingTolerance.
void run_antialiasing_diff(const RenderParams& params, const AntialiasingDiffOptions& options);

}  // namespace kinray
