#pragma once
// `kinray render --contacts`: the triangles in contact during each frame's window are tinted, so
// a user sees where things touch. The tint is applied to the shaded colour from (object, prim)
// alone, after the shading every backend shares, so tinted frames of the kinetic backend, Embree
// and OSMesa stay comparable pixel for pixel (docs/mesh_sequences.md, "Contacts in a render").
#include <cstdint>
#include <span>
#include <vector>

#include "renderer/frame.h"

namespace kinray {

/// The colour contacts are tinted towards (magenta: far from every built-in material).
inline const Color kContactColor(1.0f, 0.1f, 0.85f);
/// The share of kContactColor in a tinted pixel.
inline constexpr float kContactShare = 0.7f;

/// A triangle of the scene as one sortable key.
[[nodiscard]] inline uint64_t triangle_key(uint32_t object, uint32_t prim) {
  return uint64_t(object) << 32 | prim;
}

/// The contact window of each frame: frame i collects the contacts with time in
/// [bounds[i], bounds[i+1]) (the last window closed), bounds being the midpoints between
/// neighbouring frame times, extended by half a spacing before the first frame and after the
/// last; so with frames h apart, frame i's window is [t_i - h/2, t_i + h/2). A single frame's
/// window is the shot [shot_begin, shot_end]. Returns frame_times.size() + 1 bounds.
[[nodiscard]] std::vector<double> contact_window_bounds(std::span<const double> frame_times,
                                                        double shot_begin, double shot_end);

/// Tints every pixel of `frame` whose (object, prim) key is in `triangles` (sorted).
void tint_contacts(std::span<const uint64_t> triangles, Frame& frame);

}  // namespace kinray
