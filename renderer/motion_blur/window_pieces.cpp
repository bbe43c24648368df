#include "renderer/motion_blur/window_pieces.h"

#include <algorithm>

namespace kinray {

std::vector<double> window_breaks(const CameraSpaceScene& scene, const ShutterWindow& window) {
  std::vector<double> breaks = {window.open, window.close};
  auto cut = [&](double t) {
    if (t > window.open && t < window.close) breaks.push_back(t);
  };
  for (const CameraSpaceObject& cs : scene.objects) {
    cut(cs.appear);
    cut(cs.disappear);
    if (moves(cs))
      for (double key : cs.key_times) cut(key);
  }
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  if (breaks.size() < 2) breaks.push_back(window.close);  // a window of length 0
  return breaks;
}

}  // namespace kinray
