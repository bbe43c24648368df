#pragma once
// Each subcommand of `kinray` lives in its own file and registers itself on the CLI11 app.
// A subcommand's callback throws InputError for bad input; main prints it as one line.
#include <CLI/CLI.hpp>

namespace kinray {

void register_render_command(CLI::App& app);  // tools/render_command.cpp
void register_info_command(CLI::App& app);    // tools/info_command.cpp
void register_diff_command(CLI::App& app);    // tools/diff_command.cpp
void register_bench_command(CLI::App& app);   // tools/bench_command.cpp
void register_regress_command(CLI::App& app); // tools/regress_command.cpp
void register_ccd_queries_command(CLI::App& app);  // tools/ccd_queries_command.cpp
void register_collide_command(CLI::App& app);      // tools/collide_command.cpp
void register_video_command(CLI::App& app);   // tools/video_command.cpp

}  // namespace kinray
