// kinray: one program, one subcommand per file (tools/commands.h). Errors are caught here, once,
// and printed as one line: exit status 2 for bad input (flags, scenes, models), 1 for anything
// else.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <string>

#include "scenes/error.h"
#include "tools/commands.h"

namespace {

int fail(const std::string& message, int status) {
  std::string line = message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "kinray: error: %s\n", line.c_str());
  return status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("kinray: a kinetic ray tracer of animated scenes", "kinray");
  app.require_subcommand(1);
  kinray::register_render_command(app);
  kinray::register_info_command(app);
  kinray::register_diff_command(app);
  kinray::register_bench_command(app);
  kinray::register_regress_command(app);
  kinray::register_video_command(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help
    if (app.get_subcommands().empty() && argc > 1 && argv[1][0] != '-') {
      std::string commands;
      for (const CLI::App* command : app.get_subcommands({}))
        commands += (commands.empty() ? "" : ", ") + command->get_name();
      return fail("unknown command '" + std::string(argv[1]) + "' (commands: " + commands +
                      "; see kinray --help)",
                  2);
    }
    return fail(e.what(), 2);
  } catch (const kinray::InputError& e) {
    return fail(e.what(), 2);
  } catch (const std::exception& e) {
    return fail(e.what(), 1);
  }
  return 0;
}
