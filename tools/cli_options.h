#pragma once
// The flags that `kinray render`, `diff` and `bench` share, defined once so that they stay
// identical: each command adds the groups it needs and turns what was parsed into RenderParams.
#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>

#include "renderer/render_job.h"

namespace kinray {

/// Parse targets of the shared flags; resolve() converts and validates them.
struct RenderOptions {
  RenderParams params;  ///< flags that parse straight into their field
  std::string size = "512x512";
  int frames = 0, inbetweens = 0;
  double fps = 0;
  std::string time, aov;
  CLI::Option* size_option = nullptr;
  CLI::Option* frames_option = nullptr;
  CLI::Option* fps_option = nullptr;
  CLI::Option* inbetweens_option = nullptr;
  CLI::Option* time_option = nullptr;
  CLI::Option* aov_option = nullptr;

  /// RenderParams from the parsed flags. Throws InputError naming the flag at fault.
  [[nodiscard]] RenderParams resolve() const;
};

/// SCENE (positional, required), --animation, --keyrate.
void add_scene_options(CLI::App& command, RenderOptions& options);
/// --size, --frames | --fps | --inbetweens, --time, --threads.
void add_frame_options(CLI::App& command, RenderOptions& options);
/// --backend, --embree-mode, --packet, --sort, --light, --shadow-tree, --audit.
void add_backend_options(CLI::App& command, RenderOptions& options);
/// --camera, --eye, --target, --fov (renderer/camera_flags.h).
void add_camera_options(CLI::App& command, CameraParams& camera);
/// --out, --video, --aov, --stats, --quiet.
void add_output_options(CLI::App& command, RenderOptions& options);
/// All of the above: the flags of `kinray render`.
void add_render_options(CLI::App& command, RenderOptions& options);

/// Marks `option` as naming an output path: an empty value (an unset shell variable) is refused
/// at parse time. Commands still call check_output_file / check_output_folder
/// (renderer/output_check.h) on the paths before they start. Returns `option`.
CLI::Option* output_path(CLI::Option* option);

/// Creates `folder` (and its parents) for the output named by `flag`; an empty path is the
/// working folder. Throws InputError naming the flag when it cannot.
void create_folder(const std::filesystem::path& folder, const char* flag);

}  // namespace kinray
