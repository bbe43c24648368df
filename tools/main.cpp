// kinray: one program, one subcommand per file (tools/commands.h). Errors are caught here, once,
// and printed as one line. Exit status: 2 for bad input (flags, scenes, models, output paths that
// cannot be written), refused before anything is written; 1 for a failure of the machine or the
// program once the work has started (disk full, I/O error, out of memory) and for a failed verdict
// (diff, regress, bench).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <string>

#include "kinetic/core/rational_polynomial.h"
#include "renderer/output/temporary_files.h"
#include "tools/cli_errors.h"
#include "tools/commands.h"
#include "util/input_error.h"

namespace {

int fail(const std::string& message, int status) {
  std::string line = message;
  for (char& c : line)
    if (c == '\n' || c == '\r') c = ' ';
  std::fprintf(stderr, "kinray: error: %s\n", line.c_str());
  return status;
}

std::string kinray_version() {
  return std::string("kinray ") + KINRAY_VERSION + " (C++20; " +
#ifdef NDEBUG
         "release build"
#else
         "debug build"
#endif
         + ")";
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app("kinray: a kinetic ray tracer of animated scenes", "kinray");
  app.require_subcommand(1);
  app.set_version_flag("--version", kinray_version());
  kinray::remove_temporaries_on_interrupt();
  kinray::use_default_gmp_allocation();
  kinray::register_render_command(app);
  kinray::register_info_command(app);
  kinray::register_diff_command(app);
  kinray::register_bench_command(app);
  kinray::register_regress_command(app);
  kinray::register_ccd_queries_command(app);
  kinray::register_collide_command(app);
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
    return fail(kinray::explain_parse_error(app, e).what(), 2);
  } catch (const kinray::OptionError& e) {
    return fail(kinray::name_the_flag(e).what(), 2);
  } catch (const kinray::InputError& e) {
    return fail(e.what(), 2);
  } catch (const std::bad_alloc&) {
    return fail(
        "out of memory: the machine could not provide the memory this command needs "
        "(try a smaller --size, fewer triangles, or --backend embree)",
        1);
  } catch (const std::exception& e) {
    return fail(e.what(), 1);
  }
  return 0;
}
