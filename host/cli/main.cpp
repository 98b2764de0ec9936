// clpt: the command line. Parses, dispatches to a subcommand, and turns errors into messages on
// stderr and the documented exit codes (util/error.h).
#include <cstdio>
#include <exception>
#include <iostream>

#include "cli/commands.h"
#include "util/error.h"

int main(int argc, char** argv) {
  CLI::App app{"clpt: an OpenCL path tracer for the scenes of Computer Graphics Gems JP 2015, ch. 1"};
  app.set_version_flag("--version", std::string("clpt ") + CLPT_VERSION);
  app.require_subcommand(1);
  const auto run_render = clpt::add_render_command(app);
  const auto run_devices = clpt::add_devices_command(app);
  const auto run_bench = clpt::add_bench_command(app);
  const auto run_cache = clpt::add_cache_command(app);
#ifdef CLPT_WITH_OIIO
  const auto run_compare = clpt::add_compare_command(app);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return static_cast<int>(clpt::ExitCode::Usage);
  }
  try {
    if (app.got_subcommand("render")) return run_render();
    if (app.got_subcommand("devices")) return run_devices();
    if (app.got_subcommand("bench")) return run_bench();
    if (app.got_subcommand("cache")) return run_cache();
#ifdef CLPT_WITH_OIIO
    if (app.got_subcommand("compare")) return run_compare();
#endif
    return static_cast<int>(clpt::ExitCode::Usage);
  } catch (const clpt::Error& e) {
    std::fprintf(stderr, "clpt: error: %s\n", e.what());
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clpt: internal error: %s\n", e.what());
    return static_cast<int>(clpt::ExitCode::Failure);
  }
}
