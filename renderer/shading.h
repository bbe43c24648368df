#pragma once
// Shading shared by every backend: the backends only decide which triangle each pixel's centre
// ray hits; the colour is computed here from (object, prim) alone, so frames whose ID buffers
// agree have identical colours.
#include "renderer/frame.h"
#include "scenes/camera_space.h"

namespace kinray {

inline const Color kBackground(0.06f, 0.07f, 0.09f);

/// Base colour (or texture) with a two-sided headlight Lambert term, using vertex normals
/// interpolated at the exact hit of pixel (i, j) on (object, prim) at time t.
[[nodiscard]] Color shade_hit(const CameraSpaceScene& scene, const ImageGeometry& image, int i, int j,
                              uint32_t object, uint32_t prim, double t);

/// Fills frame.color from frame.object / frame.prim (all cores).
void shade_frame(const CameraSpaceScene& scene, Frame& frame, int threads = 0);

}  // namespace kinray
