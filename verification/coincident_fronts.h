#pragma once
// Coincident surfaces under the shutter. Where a model holds two different triangles in the same
// place (a flat panel made of overlapping fans, say, as BART's toy car is), a pixel ray meets both
// at one depth, and which of them a renderer shows is decided by its rounding, instant by instant:
// a sharp frame's diff calls such a pixel a tie (image_diff.h), and a blurred frame's colour there
// is the average of a flicker that the scene does not define. The diffs and benchmarks of blurred
// frames set such pixels aside, as the sharp diff does, once this check has found them: a pixel is
// a *coincident front* when, at one of a few instants spread over its window, its centre ray is
// strictly inside two triangles at the depth of the nearest one it pierces (within the tie
// tolerance): two triangles of a mesh that only share an edge or a vertex never are. The check is
// brute force over the triangles of every object whose box the ray meets, in double from the
// camera-space positions: independent of the backends it judges.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "renderer/frame.h"
#include "renderer/motion_blur/shutter.h"
#include "scenes/camera_space.h"
#include "verification/exact_hit.h"

namespace kinray {

/// Instants of a window at which coincident_fronts looks (the middles of as many equal strata).
inline constexpr int kCoincidenceInstants = 32;

/// Of the pixels `candidates` (row-major indices) of a width x height image, those whose centre
/// ray meets coincident nearest triangles at one of `instants` instants of `window`: a mask of
/// width x height, 1 at such a pixel.
[[nodiscard]] std::vector<uint8_t> coincident_fronts(const CameraSpaceScene& scene,
                                                     const ShutterWindow& window, int width,
                                                     int height,
                                                     const std::vector<size_t>& candidates,
                                                     int instants = kCoincidenceInstants,
                                                     const TieTolerance& tolerance = {});

/// A blurred frame's pixels that differ from their reference by more than this (largest channel,
/// linear RGB) are checked; smaller differences count in the error whatever their cause.
inline constexpr double kCoincidenceCandidateError = 0.01;

/// The coincident fronts among the pixels where blurred frame `tested` differs from `reference`
/// (both of `window`) by more than kCoincidenceCandidateError: a mask of the frames' size.
[[nodiscard]] std::vector<uint8_t> coincident_fronts(const CameraSpaceScene& scene,
                                                     const ShutterWindow& window,
                                                     const Frame& tested, const Frame& reference);

}  // namespace kinray
