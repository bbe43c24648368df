#pragma once
// `kinray diff --shutter S`: motion-blurred frames have no single id per pixel to compare, so the
// tested backend's frames are compared by colour with the Embree reference at very many time
// samples (verification/shutter_error.h), frame by frame, within a stated tolerance. Pixels
// where coincident surfaces flicker (coincident_fronts.h) are ties, set aside and drawn yellow.
#include <string>

#include "renderer/job/render_job.h"
#include "verification/shutter_error.h"

namespace kinray {

struct ShutterDiffOptions {
  int reference_samples = kShutterReferenceSamples;  ///< --reference-samples
  std::string report;         ///< --report DIR: tested, reference and error images per frame
  std::string json;           ///< --json FILE
};

/// Renders every frame with params.backend and with the reference, prints RMSE and max error per
/// frame, and throws std::runtime_error when a frame is outside ShutterTolerance.
void run_shutter_diff(const RenderParams& params, const ShutterDiffOptions& options);

}  // namespace kinray
