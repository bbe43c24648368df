#pragma once
// The flags that `kinray render`, `diff` and `bench` share, defined once so that they stay
// identical: each command adds the groups it needs and turns what was parsed into RenderParams.
#include <CLI/CLI.hpp>
#include <array>
#include <cstddef>
#include <filesystem>
#include <span>
#include <string>

#include "renderer/job/render_job.h"
#include "tools/cli/camera_flags.h"
#include "util/enum_names.h"

namespace kinray {

/// Parse targets of the shared flags; resolve() converts and validates them.
struct RenderOptions {
  RenderParams params;  ///< flags that parse straight into their field
  std::string size = "512x512";
  int frames = 0, inbetweens = 0;
  double fps = 0;
  std::string time, aov;
  std::string chunk, frame_range;   ///< --chunk I/N or slurm, --frame-range A:B
  std::vector<std::string> lights;  ///< --light, parsed by parse_light_flag
  CameraParams camera;              ///< --camera, --eye, --target, --fov: parse_camera_params
  CLI::Option* size_option = nullptr;
  CLI::Option* frames_option = nullptr;
  CLI::Option* fps_option = nullptr;
  CLI::Option* inbetweens_option = nullptr;
  CLI::Option* time_option = nullptr;
  CLI::Option* aov_option = nullptr;

  /// RenderParams from the parsed flags. Throws InputError naming the flag at fault.
  [[nodiscard]] RenderParams resolve() const;
};

/// A check that turns one of `table`'s names into its enum value; any other value is refused at
/// parse time with "FLAG: must be one of NAME, NAME, got 'VALUE'" (tools/cli_errors.h).
template <class Enum, size_t N>
[[nodiscard]] CLI::Validator enum_member(const std::array<EnumName<Enum>, N>& table) {
  return CLI::Validator(
      [table](std::string& value) {
        const auto found = find_enum(table, value);
        if (!found) return "must be one of " + enum_names(table) + ", got '" + value + "'";
        value = std::to_string(static_cast<int>(*found));  // CLI11 reads enums as integers
        return std::string();
      },
      "");
}

/// Option `flag` taking one of `table`'s names into `target`; the help shows the names and the
/// default.
template <class Enum, size_t N>
CLI::Option* add_enum_option(CLI::App& command, const std::string& flag, Enum& target,
                             const std::array<EnumName<Enum>, N>& table, const std::string& help) {
  return command.add_option(flag, target, help)
      ->transform(enum_member(table))
      ->type_name(enum_names(table, "|"))
      ->default_str(enum_name(table, target));
}

/// A check that accepts one of `allowed` only: "must be one of 1, 4, 8, 16, got '2'".
[[nodiscard]] CLI::Validator int_member(std::span<const int> allowed);

/// --size WxH into options.size (options.size_option).
CLI::Option* add_size_option(CLI::App& command, RenderOptions& options, const std::string& help);
/// --time A:B into `time`, parsed later by parse_time_range.
CLI::Option* add_time_option(CLI::App& command, std::string& time, const std::string& help);
/// --threads N (0: all cores).
CLI::Option* add_threads_option(CLI::App& command, int& threads, const std::string& help);
/// --sort list|tournament|heap (kDepthSortNames).
CLI::Option* add_sort_option(CLI::App& command, DepthSortKind& sort);

/// SCENE (positional, required), --animation, --keyrate.
void add_scene_options(CLI::App& command, RenderOptions& options);
/// --size, --frames | --fps | --inbetweens, --time, --threads.
void add_frame_options(CLI::App& command, RenderOptions& options);
/// --backend, --embree-mode, --packet, --sort, --light, --shadow-tree, --audit.
void add_backend_options(CLI::App& command, RenderOptions& options);
/// --light (repeatable) into `lights`.
CLI::Option* add_light_option(CLI::App& command, std::vector<std::string>& lights);
/// --camera, --eye, --target, --fov (tools/cli/camera_flags.h).
void add_camera_options(CLI::App& command, CameraParams& camera);
/// --out, --video, --aov, --stats, --quiet.
void add_output_options(CLI::App& command, RenderOptions& options);
/// All of the above: the flags of `kinray render`.
void add_render_options(CLI::App& command, RenderOptions& options);

/// Marks `option` as naming an output path: an empty value (an unset shell variable) is refused
/// at parse time. Commands still call check_output_file / check_output_folder
/// (renderer/output/output_check.h) on the paths before they start. Returns `option`.
CLI::Option* output_path(CLI::Option* option);

}  // namespace kinray
