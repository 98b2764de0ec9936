// clpt: the command line. Parses, dispatches to a subcommand, and turns errors into messages on
// stderr and the documented exit codes (util/error.h).
#include <cstdio>
#include <exception>

#include "cli/app.h"
#include "util/error.h"

int main(int argc, char** argv) {
  clpt::ClptApp cli;
  try {
    cli.app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return cli.app.exit(e);
  } catch (const CLI::ParseError& e) {
    cli.app.exit(e);
    return static_cast<int>(clpt::ExitCode::Usage);
  }
  try {
    return cli.chosen()();
  } catch (const clpt::Error& e) {
    std::fprintf(stderr, "clpt: error: %s\n", e.what());
    return static_cast<int>(e.code());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "clpt: internal error: %s\n", e.what());
    return static_cast<int>(clpt::ExitCode::Failure);
  }
}
