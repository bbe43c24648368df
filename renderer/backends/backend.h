#pragma once
// The interface between the frame loop and the backends (kinetic, embree, osmesa). Virtual
// dispatch is fine here: it happens once per frame, never per ray.
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <span>
#include <string>

#include "kinetic/sort/depth_sort_kind.h"
#include "renderer/antialiasing/antialiasing.h"
#include "renderer/backends/embree_build.h"
#include "renderer/frame.h"
#include "renderer/motion_blur/shutter.h"
#include "renderer/shadows/shadow_tracer.h"
#include "scenes/camera_space.h"
#include "util/work_progress.h"

namespace kinray {

/// Options every backend understands; the command line maps one flag to one field. A backend
/// rejects a bad value with an OptionError naming the field (util/input_error.h), never a flag.
struct BackendConfig {
  int width = 512, height = 512;
  int threads = 0;              ///< 0: all cores
  EmbreeBuild embree_build = EmbreeBuild::kRefit;  ///< embree: rebuild | refit the BVH
  int embree_packet = 1;        ///< embree: one of kEmbreePacketWidths
  DepthSortKind sort = DepthSortKind::kList;  ///< kinetic: per-pixel depth order
  bool audit = false;           ///< kinetic: audit every certificate between events
  ShadowTree shadow_tree = ShadowTree::aabb;  ///< kinetic: what traces shadow rays (--shadow-tree)
  ShutterParams shutter{};      ///< motion blur: samples (sampling backends), order (kinetic)
  /// Antialiasing samples per pixel of the sampling backends (a square; 1: the centre ray alone,
  /// render() then shade_frame, bit for bit as without antialiasing).
  int aa_samples = 1;
  /// --aa: exact antialiasing (the box filter from each square's visible regions; kinetic).
  Antialiasing aa = Antialiasing::none;
};

class Backend {
 public:
  virtual ~Backend() = default;
  [[nodiscard]] virtual std::string name() const = 0;
  /// Renders frame time t into `frame` (object, prim and depth; colour is filled by shade_frame).
  /// Frame times must not decrease between calls for the kinetic backend.
  virtual void render(double t, Frame& frame) = 0;
  /// The frame times render() will be asked for next, in this order (non-decreasing): a backend
  /// may render them ahead, several at a time (the kinetic grid does, band by band). A render(t)
  /// off the plan drops what is left of it and renders t as if none had been given.
  virtual void plan_frames(std::span<const double> times) {}
  /// Motion blur (renderer/motion_blur/shutter.h): frame.color is the time average of the shaded
  /// radiance over the window; object, prim and depth are those of render(window.time). Windows'
  /// open times must not decrease between calls for the kinetic backend. With BackendConfig::aa
  /// exact (kinetic) or aa_samples > 1 (embree) the average runs over the pixel's square too: the
  /// space-time box filter (renderer/antialiasing/exact_shutter.h) or its (x, y, t) samples.
  /// Throws OptionError naming the shutter when this backend has no motion blur.
  virtual void render_shutter(const ShutterWindow& window, Frame& frame);
  /// True if render_shutter is implemented (make_backend rejects --shutter otherwise).
  [[nodiscard]] virtual bool has_motion_blur() const { return false; }
  /// Antialiasing by supersampling (BackendConfig::aa_samples > 1; renderer/antialiasing/):
  /// frame.color is the mean of aa_samples shaded rays per pixel at stratified jittered positions
  /// of its square (a box filter); object, prim and depth (and the light mask) are render(t)'s, the
  /// centre ray's. Throws OptionError naming aa_samples when this backend does not supersample.
  virtual void render_supersampled(double t, Frame& frame);
  /// True if render_supersampled is implemented (make_backend rejects aa_samples > 1 otherwise).
  [[nodiscard]] virtual bool has_supersampling() const { return false; }
  /// Exact antialiasing (BackendConfig::aa == exact; renderer/antialiasing/): frame.color is the
  /// mean of the headlight's shading over each pixel's square, from the square's visible regions;
  /// object, prim and depth are render(t)'s, the centre ray's. Throws OptionError naming "aa"
  /// when this backend has none.
  virtual void render_antialiased(double t, Frame& frame);
  /// True if render_antialiased is implemented (make_backend rejects --aa exact otherwise).
  [[nodiscard]] virtual bool has_exact_antialiasing() const { return false; }
  /// Adds this backend's counters and timings to a --stats JSON object.
  virtual void write_stats(nlohmann::json& stats) const {}
  /// What traces this backend's shadow rays at the frame it rendered last; nullptr when the
  /// scene has no lights (or the backend traces no shadow rays).
  [[nodiscard]] virtual ShadowTracer* shadow_tracer() { return nullptr; }
  /// How far the work before the first frame has got (the kinetic grid's initialisation), for a
  /// progress line; nullptr when the backend has no such step.
  [[nodiscard]] virtual const WorkProgress* initialisation_progress() const { return nullptr; }
};

/// Creates the backend called `name` ("kinetic", "embree", "osmesa") for `scene`, which must
/// outlive it. Throws OptionError naming "backend" for an unknown or unavailable backend, "shutter"
/// for one without motion blur, "aa_samples" for a bad count or one without supersampling, or the
/// field of `config` a backend rejects.
std::unique_ptr<Backend> make_backend(const std::string& name, const CameraSpaceScene& scene,
                                      const BackendConfig& config);

}  // namespace kinray
