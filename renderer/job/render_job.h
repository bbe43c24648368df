#pragma once
// The frame loop shared by `kinray render`, `diff` and `bench`: RenderParams holds one field per
// command-line flag (yocto-gl's render_params), RenderJob validates them, loads the scene, fixes
// the frame times, and renders + shades frame after frame with any backend. Nothing here writes a
// file: bad input is rejected before a command touches its output.
#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/backends/backend.h"
#include "renderer/camera_choice.h"
#include "renderer/frame.h"
#include "renderer/job/frame_schedule.h"
#include "renderer/job/frame_slice.h"
#include "renderer/output/background_writes.h"
#include "scenes/camera_space.h"
#include "scenes/camera_space_lights.h"
#include "scenes/model_import.h"
#include "scenes/scene.h"

namespace kinray {

/// Every flag of `kinray render` (and of diff and bench, which share them), one field each, as
/// typed values: the command line parses the flags' text (tools/cli/).
struct RenderParams {
  std::string scene;  ///< SCENE: built-in name with parameters, .json file or model file
  std::string backend = "kinetic";                ///< --backend
  int width = 512, height = 512;                  ///< --size WxH
  std::optional<int> frames;                      ///< --frames N
  std::optional<double> fps;                      ///< --fps F
  std::optional<int> inbetweens;                  ///< --inbetweens K
  std::optional<std::pair<double, double>> time;  ///< --time A:B
  std::string out;                                ///< --out DIR; empty: out/<scene-name>
  std::string video;                              ///< --video FILE (.mp4 or .avi); empty: none
  std::vector<std::string> aov;                   ///< --aov: any of "id", "depth"
  std::string stats;                              ///< --stats FILE.json; empty: none
  int threads = 0;                                ///< --threads; 0: all cores
  EmbreeBuild embree_mode = EmbreeBuild::kRefit;  ///< --embree-mode (kEmbreeBuildNames)
  int packet = 1;                                 ///< --packet (kEmbreePacketWidths)
  DepthSortKind sort = DepthSortKind::kList;      ///< --sort (kDepthSortNames)
  bool audit = false;                             ///< --audit
  std::vector<Light> lights;                      ///< --light (repeatable): replace the scene's
  ShadowTree shadow_tree = ShadowTree::aabb;      ///< --shadow-tree (kShadowTreeNames)
  std::string animation;                          ///< --animation NAME|INDEX (model files)
  double keyrate = 0;                             ///< --keyrate HZ (model files)
  bool quiet = false;                             ///< --quiet
  bool scene_size = false;  ///< no --size given: the scene's own image size when it has one
  std::optional<FrameChunk> chunk;        ///< --chunk I/N: only the I-th of N slices
  std::optional<FrameRange> frame_range;  ///< --frame-range A:B: only frames A..B
  bool skip_existing = false;  ///< --skip-existing: render only the frames whose files are missing
  bool contacts = false;    ///< --contacts: tint the triangles in contact (set_contact_tint)
  ShutterParams shutter;  ///< --shutter, --shutter-samples, --shutter-order (motion blur)
  int aa_samples = 1;     ///< --aa-samples N: supersampled antialiasing (a square; 1: centre rays)
  Antialiasing aa = Antialiasing::none;  ///< --aa (kAntialiasingNames): exact antialiasing
  CameraChoice camera;    ///< --camera, --eye, --target, --fov
};

inline constexpr int kMaxImageSide = 16384;

/// What is wrong with `name` as an AOV ("must be one of id, depth, got '...'"), or nothing.
[[nodiscard]] std::optional<std::string> aov_problem(const std::string& name);

/// Checks every field that can be checked without the scene; throws OptionError naming the
/// field (the command line turns it into the flag), or InputError naming a flag for the checks
/// still phrased in flags (SCENE, --contacts with --shutter, and the parsers it calls).
void validate(const RenderParams& params);
/// The frame-schedule flags of `params`.
[[nodiscard]] FrameScheduleParams schedule_params(const RenderParams& params);
/// The backend flags of `params`.
[[nodiscard]] BackendConfig backend_config(const RenderParams& params);
/// The model-import flags of `params`.
[[nodiscard]] ModelOptions model_options(const RenderParams& params);
/// The default output folder name of a scene spec: "wavy-sphere:triangles=9" -> "wavy-sphere",
/// "scenes/cloth.json" -> "cloth".
[[nodiscard]] std::string scene_stem(const std::string& spec);
/// params.out, or out/<scene-name> when it is empty.
[[nodiscard]] std::string output_folder(const RenderParams& params);

/// Where the time of a frame loop went, in seconds.
struct RenderTimings {
  size_t frames = 0;
  double load = 0;    ///< loading the scene and building its camera-space flightplans
  double setup = 0;   ///< creating the backend
  double render = 0;  ///< Backend::render
  double shade = 0;   ///< shade_frame
  double write = 0;   ///< the frame sink and the wait for the background writes (files, video)
  double total = 0;   ///< wall time from the start of the job to the end of the loop
};

/// A validated, loaded scene and its frame times, ready to render with any backend.
class RenderJob {
 public:
  /// Validates `params`, loads the scene and computes the frame times; writes nothing.
  /// Throws InputError for bad flags or a bad scene.
  explicit RenderJob(RenderParams params);
  // m_camera_space points into m_scene, so the job stays where it was made.
  RenderJob(const RenderJob&) = delete;
  RenderJob& operator=(const RenderJob&) = delete;

  [[nodiscard]] const RenderParams& params() const { return m_params; }
  [[nodiscard]] const Scene& scene() const { return m_scene; }
  [[nodiscard]] const CameraSpaceScene& camera_space() const { return m_camera_space; }
  [[nodiscard]] const std::vector<double>& frame_times() const { return m_frame_times; }
  /// The frames run() renders (--chunk, --frame-range; else all), indices into frame_times().
  [[nodiscard]] const FrameSlice& slice() const { return m_slice; }
  /// The frames run() renders, in order: the slice, less those skip_frames() took out.
  [[nodiscard]] const std::vector<size_t>& frames_to_render() const { return m_to_render; }
  /// Takes the frames of the slice for which `done(index)` is true out of frames_to_render()
  /// (--skip-existing: their files are already there). The others render exactly as in a
  /// whole render: each backend is built at the first frame it renders.
  void skip_frames(const std::function<bool(size_t index)>& done);
  /// With --shutter: each frame's shutter window (renderer/motion_blur/shutter.h); empty without.
  [[nodiscard]] const std::vector<ShutterWindow>& shutter_windows() const { return m_windows; }
  /// Timings so far: load (and setup once make_backend was called).
  [[nodiscard]] const RenderTimings& timings() const { return m_timings; }

  /// Creates backend `name` (empty: params().backend) for this scene; throws InputError for an
  /// unknown backend or bad backend flags.
  [[nodiscard]] std::unique_ptr<Backend> make_backend(const std::string& name = "");
  /// With --contacts: the sorted triangle keys (contact_tint.h) to tint in each frame of the
  /// schedule, indexed like frame_times(); render_frame tints them after shading.
  void set_contact_tint(std::vector<std::vector<uint64_t>> per_frame);
  /// Renders and shades frame `index` into `frame`, adding the time spent to timings(). With
  /// lights, shadow rays go to backend.shadow_tracer() (InputError naming --backend if it has
  /// none); with --shutter the backend renders the frame's window and shades it itself (timed as
  /// render).
  void render_frame(Backend& backend, size_t index, Frame& frame);
  /// The frame loop: every frame of frames_to_render() in order (the index handed to `sink` is the
  /// one in the whole schedule), rendered, shaded and handed to `sink`, then to `writes` when given
  /// (its files written while the next frame renders, the last ones before run returns; a write's
  /// error is rethrown by the loop). Both are timed as "write": for `writes`, the time the loop
  /// waited for it. A progress bar on stderr when it is a terminal and params().quiet is false.
  /// Returns the timings of the whole job.
  const RenderTimings& run(Backend& backend,
                           const std::function<void(size_t index, const Frame&)>& sink,
                           BackgroundWrites* writes = nullptr);

 private:
  RenderParams m_params;
  Scene m_scene;
  CameraSpaceScene m_camera_space;
  CameraSpaceLights m_lights;  ///< empty: the headlight, no shadow rays
  std::unique_ptr<Backend> m_shadow_helper;  ///< Embree, for backends that trace no shadow rays
  Frame m_shadow_scratch;                    ///< the helper's primary hits, unused
  std::vector<double> m_frame_times;
  FrameSlice m_slice;
  std::vector<size_t> m_to_render;
  std::vector<ShutterWindow> m_windows;
  std::vector<std::vector<uint64_t>> m_contact_tint;  ///< empty: no --contacts
  RenderTimings m_timings;
  double m_started = 0;  ///< steady-clock seconds when the job was made
};

/// The --stats JSON: {"scene", "backend", "frames", "size", "triangles", "vertices", "objects",
/// "frame_times", "time_s": {"total", "load", "setup", "render", "shade", "write"}} plus what
/// Backend::write_stats adds.
[[nodiscard]] nlohmann::json render_stats(const RenderJob& job, const Backend& backend);

}  // namespace kinray
