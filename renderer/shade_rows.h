#pragma once
// The per-pixel loop of a frame's shading, shared by shade_frame (the headlight) and
// shade_frame_lit (lights and shadow rays): one loop over rows and pixels, what a hit pixel gets
// left to a row shader.
#include <cstddef>

#include "renderer/frame.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"
#include "util/parallel.h"

namespace kinray {

/// Shades `frame` row by row (rows in parallel, `threads` as parallel_for takes them). A pixel
/// without a hit gets kBackgroundColor; for each hit pixel of row j, left to right, the row's
/// shader `make_row(j)` is told hit(p, triangle, d, view): the pixel's index, the triangle it hits
/// at frame.time (RowTriangles), its direction and its view direction. Then finish() ends the row.
template <class MakeRow>
void shade_rows(const CameraSpaceScene& scene, Frame& frame, int threads, MakeRow&& make_row) {
  const PixelRays image{frame.width, frame.height};
  parallel_for(size_t(frame.height), threads, [&](size_t row) {
    const int j = int(row);
    auto shader = make_row(j);
    RowTriangles triangles(scene, frame.time);
    for (int i = 0; i < frame.width; ++i) {
      const size_t p = frame.index(i, j);
      if (frame.object[p] == kNoHit) {
        frame.color[p] = kBackgroundColor;
        continue;
      }
      const TriangleAtInstant& triangle = triangles.at(frame.object[p], frame.prim[p]);
      const Vec3 d = image.direction(i, j);
      shader.hit(p, triangle, d, view_direction(d, triangle.tan_half_fov));
    }
    shader.finish();
  });
}

}  // namespace kinray
