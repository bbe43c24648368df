#pragma once
// Exact antialiasing under the shutter (docs/antialiasing.md, "Under the shutter"): the
// space-time box filter, the mean of the shaded radiance over the pixel's square and the frame's
// shutter window,
//   C = 1 / (area * length) * integral over the window of (integral over the square of L dx dy) dt.
// The inner integral is exact antialiasing's read-out (exact_pixel.h) of the kinetic per-square
// sets (kinetic/squares/) at one time; the outer one is a Gauss-Legendre rule on each piece of the
// window between the breaks of its motion (renderer/motion_blur/window_pieces.h: keys, appear and
// disappear times). The sets are advanced through the window node by node, so every event is
// processed in time order, as for the still frames; the read-outs at the nodes are weighted and
// summed per pixel.
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "kinetic/squares/pixel_square_sets.h"
#include "renderer/antialiasing/exact_pixel.h"
#include "renderer/frame.h"
#include "renderer/motion_blur/shutter.h"
#include "scenes/camera_space.h"

namespace kinray {

/// A time of the outer rule and its weight (a window's weights sum to 1).
struct ShutterNode {
  double t = 0, weight = 0;
};

/// The outer rule over `window`: `rule` on each piece between window_breaks(scene, window), the
/// weights each piece's share of the window, in time order. A window of length zero is one node
/// at its time.
[[nodiscard]] std::vector<ShutterNode> space_time_nodes(const CameraSpaceScene& scene,
                                                        const ShutterWindow& window,
                                                        const GaussLegendre& rule);

/// Counters and timings of the space-time frames, for --stats ("antialiasing": "shutter").
struct ExactShutterStats {
  uint64_t windows = 0;
  uint64_t nodes = 0;     ///< read-outs of every pixel's square, summed over the windows
  uint64_t rebuilds = 0;  ///< sets built again because a window opened before their time
  double events_s = 0;    ///< advancing the sets through the windows (and the gaps)
  double readout_s = 0;   ///< the exact read-outs at the nodes and their sum
};

class ExactShutter {
 public:
  /// Builds the per-square sets at a given time (the kinetic backend's: its grid input, audit).
  using MakeSets = std::function<std::unique_ptr<PixelSquareSets>(double t)>;

  /// `order` Gauss-Legendre nodes per piece (0: kDefaultShutterOrder); rows in parallel on
  /// `threads`; `make_sets` builds the sets at the first node.
  ExactShutter(const CameraSpaceScene& scene, int order, int threads, MakeSets make_sets);

  /// frame.color: the space-time box filter of every pixel over `window`; frame.time is
  /// window.time; object, prim and depth are left as they are (the centre ray's at the frame
  /// time, which the caller reads). A window that opens before the sets' time (overlapping
  /// windows of an irregular schedule) builds the sets again at its first node.
  void render(const ShutterWindow& window, Frame& frame);

  [[nodiscard]] const PixelSquareSets* sets() const { return m_sets.get(); }
  [[nodiscard]] const ExactShutterStats& stats() const { return m_stats; }
  [[nodiscard]] const ExactPixels::Stats& readout_stats() const { return m_readout; }
  [[nodiscard]] int order() const { return int(m_rule.nodes.size()); }

 private:
  const CameraSpaceScene& m_scene;
  GaussLegendre m_rule;
  int m_threads;
  MakeSets m_make_sets;
  std::unique_ptr<PixelSquareSets> m_sets;
  std::vector<ColorAverage> m_average;  ///< per pixel, over the window's nodes
  ExactShutterStats m_stats;
  ExactPixels::Stats m_readout;
};

}  // namespace kinray
