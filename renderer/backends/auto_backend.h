#pragma once
// `--backend auto`, render's default: the faster of the kinetic grid and Embree for the shot at
// hand, measured on the shot itself. The grid pays an initialisation and then a cost per event,
// however many frames share them; Embree pays a cost per frame. The break-even moves with the
// scene and the image (about 10 frames per keyframe interval on wavy-sphere, 60 on flythrough,
// 100 on BART), so no rule of thumb decides it; what the first frames cost does:
//   1. Embree (refit, its widest native packet up to 8) renders the first two frames: its BVH
//      build and the cost of one more frame, E.
//   2. When the shot has fewer than kMinFramesPerInterval frames per keyframe interval, or the
//      frames left cost less with Embree than kInitInEmbreeBuilds first Embree frames (the grid's
//      initialisation is 7-35 of them on the built-in scenes), Embree renders the rest: the
//      grid could not pay its initialisation back.
//   3. Otherwise the grid is built at the third frame and renders the frames of that frame's
//      keyframe interval: the interval's events and read-outs give its cost per second of shot.
//      Projected over the rest of the shot against E per frame left, the cheaper one renders the
//      rest; if that is Embree, the grid's initialisation and one interval were the price of
//      finding out.
//   4. The choice of the grid is checked at the end of every keyframe interval it renders: a
//      shot's events per interval vary along it (flythrough's camera meets denser geometry), and
//      one interval is a small sample. When kGridLostIntervals intervals in a row cost the grid
//      more than kGridCheckMargin times E per frame it rendered, Embree renders the rest (one
//      slow interval may be another process's moment on a shared machine).
// Every frame is its backend's exact frame: the grid built at any frame renders what a grid
// built at the first would (docs/render_farm.md), and Embree refits to any time, so a frame of an
// auto render equals the same frame of whichever backend rendered it. Flags that only one backend
// reads choose it outright (--sort, --audit, --shadow-tree, --shutter, --aa exact: kinetic;
// --packet, --embree-mode, --aa-samples: Embree, also with --shutter).
#include <memory>

#include "renderer/backends/backend.h"

namespace kinray {

/// The frames left after Embree's first two must cost more than this many first Embree frames
/// (its BVH build and trace) before the grid is tried.
inline constexpr double kInitInEmbreeBuilds = 20;
/// Nor is it tried with fewer frames per keyframe interval than this: its break-even lies at 6
/// to more than 60 on the scenes measured (docs/performance.md, 6 only on small collision scenes
/// and static-moving), and a trial below it costs the initialisation for nothing on most.
inline constexpr double kMinFramesPerInterval = 8;

/// The grid keeps the shot while each keyframe interval costs it at most this many times what
/// Embree's measured frame would have cost for the same frames: wide enough that the noise of a
/// shared machine does not hand a shot back and forth, narrow enough to catch a wrong choice.
inline constexpr double kGridCheckMargin = 1.5;
/// How many keyframe intervals in a row must lose by that margin before Embree takes the rest:
/// a shot that turns against the grid for good loses every interval, a moment of load one.
inline constexpr int kGridLostIntervals = 2;

/// Whether the grid, having spent `grid_seconds` on `frames` frames of one keyframe interval, lost
/// to Embree at `embree_frame_seconds` a frame by more than kGridCheckMargin.
[[nodiscard]] constexpr bool grid_lost_interval(double grid_seconds, size_t frames,
                                                double embree_frame_seconds) {
  return frames > 0 && grid_seconds > kGridCheckMargin * embree_frame_seconds * double(frames);
}

/// The auto backend for `scene` (or the kinetic or Embree backend itself when a flag of `config`
/// chooses it). Its stats hold "auto": how many frames each backend rendered, the costs measured
/// and the decisions, with a one-line "summary".
[[nodiscard]] std::unique_ptr<Backend> make_auto_backend(const CameraSpaceScene& scene,
                                                         const BackendConfig& config);

}  // namespace kinray
