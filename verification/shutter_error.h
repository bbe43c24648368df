#pragma once
// The error of a motion-blurred frame against a reference: the reference is the Embree motion
// blur with very many stratified time samples per pixel (kShutterReferenceSamples), whose own
// visibility error at a pixel is at most (front changes in the window) x (contrast) / samples.
// Errors are in linear RGB in [0, 1], over every channel of every pixel.
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/frame.h"
#include "verification/color_diff.h"

namespace kinray {

/// Time samples per pixel of the reference frame unless --reference-samples says otherwise.
inline constexpr int kShutterReferenceSamples = 4096;

/// What `kinray diff --shutter` accepts per frame (linear RGB): the kinetic frame is exact up to
/// the quadrature of the shading and float rounding, so nearly all of its difference is the
/// reference's own sampling error, which these bounds leave room for at 4096 samples.
struct ShutterTolerance : ColorTolerance {
  ShutterTolerance() : ColorTolerance{2e-3, 0.05} {}
};

/// Writes |a - b| (largest channel per pixel), times `gain`, as a grey-to-red 8-bit PNG: black
/// where equal, yellow where `aside` (a mask of the frames' size, or nullptr) sets a pixel aside
/// as a tie. Throws InputError when the file cannot be written.
void write_error_png(const Frame& a, const Frame& b, const std::string& path, double gain = 10,
                     const std::vector<uint8_t>* aside = nullptr);

}  // namespace kinray
