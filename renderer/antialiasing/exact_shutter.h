#pragma once
// Exact antialiasing under the shutter (docs/antialiasing.md, "Under the shutter"): the
// space-time box filter, the mean of the shaded radiance over the pixel's square and the frame's
// shutter window,
//   C = 1 / (area * length) * integral over the window of g(t) dt,  g(t) = integral over the
//   square of L(x, y, t) dx dy.
// g(t) is exact antialiasing's read-out (exact_pixel.h) of the kinetic per-square sets
// (kinetic/squares/) at t; the time integral is a Gauss-Legendre rule on each piece of the window.
//
// g is smooth only between the pixel's events: where a triangle enters or leaves the square, or
// crosses into a neighbour's, its visible area turns. So each pixel's window is cut at the breaks
// of the motion (renderer/motion_blur/window_pieces.h: keys, appear and disappear times; the
// window's nodes shared by those pieces in proportion to their length, two at least) and at
// the times the sets' change log (square_change_log.h) gives for it: its own set's changes, and
// its neighbours' changes of triangles its set holds. A piece of the motion with a few such
// events is cut there, each part taking the rule's nodes in proportion to its length (at least
// one), so a pixel costs at most the events more read-outs than the fixed rule; a piece with more
// events than nodes keeps the whole rule. The sets are advanced through the window
// once, with the log on; the union of a pixel's set at the close and the triangles in its log
// holds every triangle that overlaps its square at any time of the window, so it reads the pixel
// out at any node (the read-out clips each triangle exactly at its time; extra ones do no harm).
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

/// Counters and timings of the space-time frames, for --stats ("antialiasing": "shutter").
struct ExactShutterStats {
  uint64_t windows = 0;
  uint64_t readouts = 0;      ///< pixel read-outs at a node, summed over the windows
  uint64_t pieces = 0;        ///< pixel pieces between cuts, summed over the windows
  uint64_t still_pixels = 0;  ///< pixels read once: nothing over their square moves in the window
  uint64_t changes = 0;       ///< entries into and exits from the pixels' sets inside the windows
  uint64_t rebuilds = 0;      ///< sets built again because a window opened before their time
  double events_s = 0;        ///< advancing the sets through the windows (and the gaps)
  double readout_s = 0;       ///< the read-outs and their sums
};

class ExactShutter {
 public:
  /// Builds the per-square sets at a given time (the kinetic backend's: its grid input, audit).
  using MakeSets = std::function<std::unique_ptr<PixelSquareSets>(double t)>;

  struct Config {
    /// Gauss-Legendre nodes per piece (0: kDefaultShutterOrder).
    int order = 0;
    /// Cut each pixel's window at its events (the change log); false: at the motion's breaks
    /// only, one fixed rule for every pixel (what the error analysis of the cuts is against).
    bool cut_at_events = true;
  };

  /// Rows in parallel on `threads`; `make_sets` builds the sets at the first window's open time.
  ExactShutter(const CameraSpaceScene& scene, const Config& config, int threads,
               MakeSets make_sets);

  /// frame.color: the space-time box filter of every pixel over `window`; frame.time is
  /// window.time; object, prim and depth are left as they are (the centre ray's at the frame
  /// time, which the caller reads). A window that opens before the sets' time (overlapping
  /// windows of an irregular schedule) builds the sets again at its open time.
  void render(const ShutterWindow& window, Frame& frame);

  [[nodiscard]] const PixelSquareSets* sets() const { return m_sets.get(); }
  [[nodiscard]] const ExactShutterStats& stats() const { return m_stats; }
  [[nodiscard]] const ExactPixels::Stats& readout_stats() const { return m_readout; }
  [[nodiscard]] int order() const { return int(m_rules.size()); }

 private:
  const CameraSpaceScene& m_scene;
  Config m_config;
  std::vector<GaussLegendre> m_rules;  ///< the rules of 1 .. order nodes (the window's is the last)
  int m_threads;
  MakeSets m_make_sets;
  std::unique_ptr<PixelSquareSets> m_sets;
  std::vector<uint8_t> m_moves;  ///< per object: its camera-space positions change
  bool m_fixed_fov = false;      ///< the shading's view directions do not change with time
  std::vector<uint32_t> m_change_begin, m_change_order;  ///< the log by pixel, in time order
  ExactShutterStats m_stats;
  ExactPixels::Stats m_readout;
};

}  // namespace kinray
