#include "cli/app.h"

#include "cli/commands.h"
#include "util/error.h"

namespace clpt {

ClptApp::ClptApp() {
  app.set_version_flag("--version", std::string("clpt ") + CLPT_VERSION);
  app.require_subcommand(1);
  commands.emplace_back("render", add_render_command(app));
  commands.emplace_back("devices", add_devices_command(app));
  commands.emplace_back("bench", add_bench_command(app));
  commands.emplace_back("cache", add_cache_command(app));
  commands.emplace_back("scene-transform", add_scene_transform_command(app));
  commands.emplace_back("kernels", add_kernels_command(app));
  commands.emplace_back("verify", add_verify_command(app));
#ifdef CLPT_WITH_OIIO
  commands.emplace_back("compare", add_compare_command(app));
  commands.emplace_back("tradeoff", add_tradeoff_command(app));
#endif
}

const std::function<int()>& ClptApp::chosen() const {
  for (const auto& [name, run] : commands)
    if (app.got_subcommand(name)) return run;
  throw Error(ExitCode::Usage, "no subcommand given (see clpt --help)");
}

}  // namespace clpt
