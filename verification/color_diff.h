#pragma once
// The frame loop of the diffs that judge by colour (`diff --shutter`, `diff --aa`): frames with
// no single id per pixel, compared with a reference that samples very densely, frame by frame,
// against a per-frame tolerance in linear RGB, with a line per frame and optional report images.
#include <cstddef>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "renderer/backends/backend.h"
#include "renderer/job/render_job.h"
#include "verification/image_diff.h"

namespace kinray {

/// What a diff by colour accepts per frame: its RMSE and its largest channel error.
struct ColorTolerance {
  double rmse = 0;
  double max_error = 0;
  [[nodiscard]] bool met(const ColorError& e) const;
};

/// The frames' errors against the reference.
struct ColorDiffFrames {
  nlohmann::json per_frame = nlohmann::json::array();  ///< frame, time, rmse, max_error, within
  size_t outside = 0;                                  ///< frames outside the tolerance
  double rmse = 0;  ///< pooled over every channel of every pixel of every frame
  double worst_rmse = 0, worst_max_error = 0;
  size_t ties = 0;  ///< pixels set aside, over every frame
};

/// The pixels of frame `index` to set aside as ties, given the tested and the reference frame:
/// a mask of the frames' size.
using TiePixels = std::function<std::vector<uint8_t>(size_t, const Frame&, const Frame&)>;

/// Renders every frame of `job` with `tested` (through the job, as `render` would) and with
/// `reference(index, frame)`, compares them by colour (but for the pixels `ties` sets aside, when
/// given), prints a line per frame unless `quiet`, and writes tested_NNNNN.png,
/// reference_NNNNN.png and error_NNNNN.png into `report` when it is not empty (a folder that must
/// exist).
[[nodiscard]] ColorDiffFrames diff_frames_by_color(
    RenderJob& job, Backend& tested, const std::function<void(size_t, Frame&)>& reference,
    const ColorTolerance& tolerance, const std::string& report, bool quiet,
    const TiePixels& ties = {});

}  // namespace kinray
