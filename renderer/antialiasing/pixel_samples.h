#pragma once
// Stratified jittered sample positions inside a pixel's square, for the sampling peer of exact
// antialiasing (renderer/antialiasing/embree_supersampling.h): n = m x m strata, one uniform
// jitter in each, drawn from a hash of (pixel, sample, n) so that a frame is the same whatever
// the threads and the run, and runs at different sample counts are not correlated.
#include <cstdint>
#include <string>

#include "renderer/antialiasing/square_visibility.h"
#include "util/input_error.h"

namespace kinray {

/// The largest number of antialiasing samples per pixel (a square: 256 x 256).
inline constexpr int kMaxAaSamples = 65536;

/// The m of n = m x m, or 0 when n is not the square of a positive integer.
[[nodiscard]] inline int sample_grid_side(int n) {
  for (int m = 1; m * m <= n; ++m)
    if (m * m == n) return m;
  return 0;
}

/// Whether n is a count of antialiasing samples per pixel: a square in 1..kMaxAaSamples.
[[nodiscard]] inline bool is_aa_sample_count(int n) {
  return n <= kMaxAaSamples && sample_grid_side(n) != 0;
}

/// Throws OptionError naming "aa_samples" unless is_aa_sample_count(n).
inline void check_aa_samples(int n) {
  if (!is_aa_sample_count(n))
    throw OptionError("aa_samples", "must be a square in 1.." + std::to_string(kMaxAaSamples) +
                                        " (1, 4, 16, 64, ...), got " + std::to_string(n));
}

/// splitmix64: a well-spread 64-bit hash.
[[nodiscard]] inline uint64_t splitmix64(uint64_t z) {
  z += 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

/// Sample k of m x m in `square` of the pixel with index `pixel`: stratum (k % m, k / m),
/// jittered uniformly inside it.
[[nodiscard]] inline Vec2 pixel_sample(const PixelSquare& square, uint64_t pixel, int k, int m) {
  const uint64_t h = splitmix64(splitmix64(pixel * 0x100000001B3ull + uint64_t(m)) + uint64_t(k));
  const double u = double(h >> 40) * 0x1.0p-24, v = double((h >> 16) & 0xFFFFFF) * 0x1.0p-24;
  return {square.x0 + (square.x1 - square.x0) * ((k % m + u) / m),
          square.y0 + (square.y1 - square.y0) * ((k / m + v) / m)};
}

}  // namespace kinray
