#pragma once
// Exact motion blur on the kinetic grid (docs/design.md, "Exact motion blur"). The grid
// processes every event of a shutter window in time order and logs each change of a pixel's front
// (kinetic/grid/front_change_log.h); between two changes the front is fixed, so each pixel's window
// splits into intervals with one front each, and the visibility part of the time average is
// exact. Each interval's shading (which varies smoothly while the front is fixed) is integrated
// by Gauss-Legendre quadrature; the background counts for its share of the window.
//
// With lights, each interval's shading is integrated piecewise between the changes of its light
// mask (shutter_shadows.h), and the light mask AOV is the front's at the frame time.
//
// The timeline keeps the fronts at the open time of the last window and the grid's log of the
// changes since, so windows may overlap (an irregular schedule): the grid only ever moves forward.
#include <array>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "kinetic/core/counters.h"
#include "kinetic/grid/frustum_grid.h"
#include "renderer/frame.h"
#include "renderer/motion_blur/shutter.h"
#include "renderer/motion_blur/shutter_shadows.h"
#include "renderer/shading.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

// X(member, "stats key") of KineticShutterStats (kinetic/core/counters.h).
#define KINRAY_SHUTTER_COUNTERS(X)                                                            \
  X(front_changes, "front_changes") /* logged changes inside the windows */                   \
  X(pixels_split, "pixels_split")   /* pixels whose window has several intervals */           \
  X(shading_nodes, "shading_nodes") /* shadings of a front at a node (background excluded) */ \
  X(shadow_rays, "shadow_rays")     /* with lights: traced at probes and bisections */        \
  X(mask_changes, "mask_changes")   /* with lights: change times of a light mask found */

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
  /// `order` Gauss-Legendre nodes per interval (0: kDefaultShutterOrder). With `lights` (not
  /// empty; they must outlive this) the shading is lit and shadowed, else the headlight's.
  KineticShutter(const CameraSpaceScene& scene, int order, int threads,
                 const CameraSpaceLights* lights = nullptr);

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
  /// Calls visit(t, weight, next) for each quadrature node of `object` over [t0, t1], the
  /// weights shares of a window of length `length`; the node's piece lies in [keys[next - 1],
  /// keys[next]] of the object's key times.
  template <class Visit>
  void for_each_node(uint32_t object, double t0, double t1, double length, Visit&& visit) const;
  /// The nodes of each object over the whole window, shared by every pixel whose front stays.
  void place_window_nodes(const ShutterWindow& window);
  /// The triangles over key segments built last, in a small direct-mapped table (one per
  /// thread): the fronts whose intervals close near each other in a band's log, or along a row,
  /// are few, and each shades four nodes per interval from one TriangleOverSegment.
  class SegmentCache {
   public:
    [[nodiscard]] const TriangleOverSegment& get(const CameraSpaceScene& scene, uint32_t object,
                                                 uint32_t prim, size_t k) {
      TriangleOverSegment& slot = m_slots[(prim * 0x9E3779B1u + object * 31u + k) % kSlots];
      if (!slot.holds(object, prim, k)) slot = TriangleOverSegment(scene, object, prim, k);
      return slot;
    }

   private:
    static constexpr size_t kSlots = 64;
    std::array<TriangleOverSegment, kSlots> m_slots;
  };
  /// Adds the front's shading over [t0, t1] (of a window of length `length`) to `average`, and
  /// the nodes it shaded (and, with lights, the shadow rays it traced) to `counts`.
  void integrate(const GridScene& grid, uint32_t front, int i, int j, double t0, double t1,
                 double length, SegmentCache& cache, ShutterShadowCounts& counts,
                 ColorAverage& average) const;
  /// A front's triangle at each node of the window, kept while the next pixel has the same front.
  struct FrontNodes {
    uint32_t front = kNoGridHit;
    std::vector<TriangleAtInstant> triangles;  ///< one per node of its object's window nodes
  };
  /// A pixel's view direction, computed again only when the fov changes between nodes.
  class ViewCache {
   public:
    const Eigen::Vector3f& at(const Vec3& d, double tan_half_fov) {
      if (!(tan_half_fov == m_tan)) {
        m_tan = tan_half_fov;
        m_view = view_direction(d, tan_half_fov);
      }
      return m_view;
    }

   private:
    double m_tan = std::numeric_limits<double>::quiet_NaN();
    Eigen::Vector3f m_view;
  };
  /// shading_instant(m_scene, object, t) bit for bit, for a node of for_each_node's piece
  /// `next`: the key segment without a search, the fov's tangent from m_fixed_tan_half_fov.
  [[nodiscard]] ShadingInstant instant(uint32_t object, double t, size_t next) const;
  /// Adds the front's shading over the whole window (the nodes of place_window_nodes); `memo`
  /// holds the last front's triangle at those nodes.
  void integrate_window(const GridScene& grid, uint32_t front, int i, int j, FrontNodes& memo,
                        SegmentCache& cache, ShutterShadowCounts& counts,
                        ColorAverage& average) const;

  /// The rule of `object`'s intervals: m_textured_rule for a textured object, else m_rule.
  [[nodiscard]] const GaussLegendre& rule(uint32_t object) const {
    return m_textured[object] ? m_textured_rule : m_rule;
  }

  const CameraSpaceScene& m_scene;
  GaussLegendre m_rule;
  /// A textured front's shading varies at the scale of its texels, which slide under the pixel
  /// as it moves: it gets at least kTexturedShutterOrder nodes per interval, each showing its
  /// texture's mean over the node's cell (texture_path.h).
  GaussLegendre m_textured_rule;
  std::vector<uint8_t> m_textured;            ///< per object
  std::unique_ptr<ShutterShadows> m_shadows;  ///< with lights
  int m_threads;
  std::optional<double> m_fixed_tan_half_fov;  ///< set when the fov is the same at every key
  bool m_started = false;
  std::vector<uint32_t> m_open_front;  ///< per pixel, global triangle id at the last open time
  /// A quadrature node over the whole window: the shading instant and its weight.
  struct WindowNode {
    ShadingInstant instant;
    double weight = 0;
  };
  std::vector<std::vector<WindowNode>> m_window_nodes;  ///< per object, for the current window
  ShutterWindow m_window;                               ///< the current window
  /// A pixel whose front changes inside the window: its open interval (the front since `since`),
  /// the average of the intervals closed so far, and its front at the frame time.
  struct alignas(64) SplitPixel {
    ColorAverage average;
    double since = 0;
    uint32_t front = 0;
    uint32_t at_time = 0;
  };
  static constexpr uint32_t kNotSplit = ~0u;
  std::vector<SplitPixel> m_split;      ///< the window's split pixels, kept across windows
  std::vector<uint32_t> m_split_index;  ///< per pixel, its SplitPixel or kNotSplit
  std::vector<uint32_t> m_split_at_time;  ///< per pixel: a split pixel's at_time (row pass)
  KineticShutterStats m_stats;
};

}  // namespace kinray
