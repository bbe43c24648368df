#include "renderer/contact_tint.h"

#include <algorithm>

namespace kinray {

std::vector<double> contact_window_bounds(std::span<const double> frame_times, double shot_begin,
                                          double shot_end) {
  const size_t n = frame_times.size();
  if (n == 0) return {};
  if (n == 1) return {shot_begin, shot_end};
  std::vector<double> bounds(n + 1);
  bounds[0] = frame_times[0] - 0.5 * (frame_times[1] - frame_times[0]);
  for (size_t i = 1; i < n; ++i) bounds[i] = 0.5 * (frame_times[i - 1] + frame_times[i]);
  bounds[n] = frame_times[n - 1] + 0.5 * (frame_times[n - 1] - frame_times[n - 2]);
  return bounds;
}

void tint_contacts(std::span<const uint64_t> triangles, Frame& frame) {
  if (triangles.empty()) return;
  for (size_t p = 0; p < frame.pixel_count(); ++p) {
    if (frame.object[p] == kNoHit) continue;
    if (std::binary_search(triangles.begin(), triangles.end(),
                           triangle_key(frame.object[p], frame.prim[p])))
      frame.color[p] = (1 - kContactShare) * frame.color[p] + kContactShare * kContactColor;
  }
}

}  // namespace kinray
