#pragma once
// Exact motion blur on the kinetic grid (DESIGN.md, "Exact motion blur"). The grid processes
// every event of a shutter window in time order and logs each change of a pixel's front
// (kinetic/grid/front_change_log.h); between two changes the front is fixed, so each pixel's window
// splits into intervals with one front each, and the visibility part of the time average is
// exact. Each interval's shading (which varies smoothly while the front is fixed) is integrated
// by Gauss-Legendre quadrature; the background counts for its share of the window.
//
// The timeline keeps the fronts at the open time of the last window and the grid's log of the
// changes since, so windows may overlap (an irregular schedule): the grid only ever moves forward.
#include <cstdint>
#include <vector>

#include "kinetic/core/counters.h"
#include "kinetic/grid/frustum_grid.h"
#include "renderer/frame.h"
#include "renderer/shading.h"
#include "renderer/shutter.h"
#include "scenes/camera_space.h"

namespace kinray {

// X(member, "stats key") of KineticShutterStats (kinetic/core/counters.h).
#define KINRAY_SHUTTER_COUNTERS(X)                                                   \
  X(front_changes, "front_changes") /* logged changes inside the windows */         \
  X(pixels_split, "pixels_split")   /* pixels whose window has several intervals */ \
  X(shading_nodes, "shading_nodes") /* shade_hit calls */

/// Counters and timings of the blurred frames, for --stats ("shutter").
struct KineticShutterStats {
  KINRAY_SHUTTER_COUNTERS(KINRAY_COUNTER_FIELD)
  KINRAY_COUNTER_SECTION(for_each_counter, KINRAY_SHUTTER_COUNTERS)
  double events_s = 0;         ///< seconds advancing the grid through the windows (and gaps)
  double integrate_s = 0;      ///< seconds walking the logs and integrating the shading
  double readout_s = 0;        ///< seconds reading the ids and depths at the frame times
};

class KineticShutter {
 public:
  /// `order` Gauss-Legendre nodes per interval (0: kDefaultShutterOrder).
  KineticShutter(const CameraSpaceScene& scene, int order, int threads);

  /// Renders `window` from `grid` (at a time <= window.open on the first call; the grid is
  /// advanced to window.close): frame.color is the time average over the window; object, prim
  /// and depth are the front at window.time, as the sharp frame has them.
  void render(FrustumGrid& grid, const ShutterWindow& window, Frame& frame);

  [[nodiscard]] const KineticShutterStats& stats() const { return m_stats; }
  [[nodiscard]] int order() const { return int(m_rule.nodes.size()); }

 private:
  /// On the first call: the fronts at the grid's time, and every later change logged.
  void start_logging(FrustumGrid& grid);
  /// Brings the fronts to time `open` (the grid is at or after it): applies and drops the logged
  /// changes up to it.
  void roll_to(FrustumGrid& grid, double open);
  /// Calls visit(t, weight) for each quadrature node of `object` over [t0, t1], the weights
  /// shares of a window of length `length`.
  template <class Visit>
  void for_each_node(uint32_t object, double t0, double t1, double length, Visit&& visit) const;
  /// The nodes of each object over the whole window, shared by every pixel whose front stays.
  void place_window_nodes(const ShutterWindow& window);
  /// Adds the front's shading over [t0, t1] (of a window of length `length`) to `average`.
  void integrate(const GridScene& grid, uint32_t front, int i, int j, double t0, double t1,
                 double length, ColorAverage& average) const;
  /// Adds the front's shading over the whole window (the nodes of place_window_nodes).
  void integrate_window(const GridScene& grid, uint32_t front, int i, int j,
                        ColorAverage& average) const;

  const CameraSpaceScene& m_scene;
  GaussLegendre m_rule;
  int m_threads;
  bool m_started = false;
  std::vector<uint32_t> m_open_front;  ///< per pixel, global triangle id at the last open time
  /// A quadrature node over the whole window: the shading instant and its weight.
  struct WindowNode {
    ShadingInstant instant;
    double weight = 0;
  };
  std::vector<std::vector<WindowNode>> m_window_nodes;  ///< per object, for the current window
  KineticShutterStats m_stats;
};

}  // namespace kinray
