#pragma once
// Motion blur as Embree's users do it (Embree 3 tutorial "motion_blur_geometry"): geometries
// with several time steps, rays at stratified times inside the shutter (ray.time in [0, 1]), the
// linear interpolation between time steps done by Embree. The flightplans are piecewise linear
// with breaks at their keys, and Embree spaces a geometry's time steps evenly over its time range,
// so a window whose keys are not evenly spaced inside it cannot be one geometry without
// resampling the motion. Instead the window is cut at every key (and every appear / disappear
// time) inside it, and each piece gets its own scene whose moving geometries have two time steps,
// the camera-space positions at the piece's ends: within a piece that is exactly the flightplan,
// and each ray is traced in the piece its time falls in. Static objects are one geometry shared
// by every piece. N samples per pixel, stratified with a fixed per-pixel jitter. With lights, each
// sample's hit traces one shadow ray per light through the same piece at the same ray time, and
// is shaded as renderer/shadows/lighting.h shades a sharp frame's.
//
// With antialiasing samples (--aa-samples N > 1 with --shutter), the samples spread over the
// pixel's square too, the sampling peer of the exact space-time box filter: N = m x m spatial
// strata jittered as the still supersampler jitters them (renderer/antialiasing/pixel_samples.h),
// and N time strata of the window dealt to them by a per-pixel shuffle (a Latin hypercube in
// (x, y) x t), each sample traced through the piece its time falls in.
#include <embree3/rtcore.h>

#include <nlohmann/json_fwd.hpp>
#include <vector>

#include "renderer/frame.h"
#include "renderer/motion_blur/shutter.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"

namespace kinray {

class EmbreeMotionBlur {
 public:
  /// `device` must outlive this; `samples` time samples per pixel at its centre, or, when
  /// `aa_samples` > 1 (a square), that many samples in (x, y, t) instead. With `lights` (not
  /// empty; they must outlive this) samples are lit and shadowed, else lit by the headlight.
  EmbreeMotionBlur(const CameraSpaceScene& scene, RTCDevice device, int threads, int samples,
                   const CameraSpaceLights* lights = nullptr, int aa_samples = 1);
  ~EmbreeMotionBlur();
  EmbreeMotionBlur(const EmbreeMotionBlur&) = delete;
  EmbreeMotionBlur& operator=(const EmbreeMotionBlur&) = delete;

  /// frame.color: the mean of the shaded samples of each pixel over the window; object, prim
  /// and depth (and with lights the light mask): the hit at window.time (one more ray per pixel).
  void render(const ShutterWindow& window, Frame& frame);
  /// Adds "motion_blur": {samples, pieces, build_s, trace_s (totals and per frame)}.
  void write_stats(nlohmann::json& stats) const;

 private:
  /// One scene per piece of the window; the times where the pieces meet.
  void build(const ShutterWindow& window);
  void release_pieces();
  RTCGeometry new_geometry(size_t object, unsigned time_steps) const;

  const CameraSpaceScene& m_scene;
  const CameraSpaceLights* m_lights = nullptr;  ///< nullptr: the headlight
  RTCDevice m_device;
  int m_threads;
  int m_samples;
  int m_aa_samples = 1;               ///< > 1: samples in (x, y, t), a square
  uint64_t m_frame = 0;               ///< seeds the jitter: each frame draws fresh times
  std::vector<RTCGeometry> m_static;  ///< per object: its shared geometry if it never moves
  std::vector<double> m_breaks;       ///< piece k is [m_breaks[k], m_breaks[k + 1]]
  std::vector<RTCScene> m_pieces;
  std::vector<RTCGeometry> m_moving;  ///< this frame's moving geometries, released with the pieces
  std::vector<double> m_build_s, m_trace_s;
  std::vector<size_t> m_piece_counts;
};

}  // namespace kinray
