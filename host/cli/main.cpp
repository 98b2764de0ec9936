// clpt: the command line. Parses, dispatches to a subcommand, and turns errors into messages on
// stderr and the documented exit codes (util/error.h). In an MPI job (render/rank_group.h) an
// error that all ranks share (render/rank_pass.h, JobError) is printed by rank 0 and the ranks
// leave the job in order; any other error names its rank and host and ends the whole job, since
// the other ranks would wait for this one for ever.
#include <cstdio>
#include <exception>
#include <string>

#include "cli/app.h"
#ifdef CLPT_WITH_OIIO
#include "io/image_io.h"
#endif
#include "render/rank_group.h"
#include "render/rank_pass.h"
#include "util/error.h"

namespace {

// Prints `message` as this rank's error and returns `code`, or does not return when the job
// must end with it.
int fail(const char* kind, const std::string& message, int code, bool shared_by_every_rank) {
  clpt::RankGroup* ranks = clpt::existing_rank_group();
  if (!ranks || ranks->size() == 1) {
    std::fprintf(stderr, "clpt: %s: %s\n", kind, message.c_str());
    if (ranks) ranks->finish();
    return code;
  }
  if (shared_by_every_rank) {
    if (ranks->coordinator()) std::fprintf(stderr, "clpt: %s: %s\n", kind, message.c_str());
    ranks->finish();
    return code;
  }
  std::fprintf(stderr, "clpt: %s: %s: %s\n", kind, clpt::rank_label(*ranks, ranks->rank(), ranks->host()).c_str(),
               message.c_str());
  std::fflush(stderr);
  ranks->abort(code);
  return code;  // not reached: abort ends the process
}

}  // namespace

int main(int argc, char** argv) {
#ifdef CLPT_WITH_OIIO
  clpt::install_scene_image_reader();  // textures and environment files (scene/scene_image.h)
#endif
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
    const int code = cli.chosen()();
    if (clpt::RankGroup* ranks = clpt::existing_rank_group()) ranks->finish();
    return code;
  } catch (const clpt::JobError& e) {
    return fail("error", e.what(), static_cast<int>(e.code()), true);
  } catch (const clpt::Error& e) {
    return fail("error", e.what(), static_cast<int>(e.code()), false);
  } catch (const std::exception& e) {
    return fail("internal error", e.what(), static_cast<int>(clpt::ExitCode::Failure), false);
  }
}
