// `clpt cache dir|clear`: where the kernel binary cache lives, and emptying it. Entries can never
// be stale (cl/kernel_cache.h), so clearing is only ever needed to reclaim disk space.
#include <cstdio>

#include "cl/kernel_cache.h"
#include "cli/commands.h"
#include "util/error.h"

namespace clpt {

std::function<int()> add_cache_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("cache", "The kernel binary cache: `cache dir` prints where it "
                                              "is, `cache clear` empties it");
  cmd->require_subcommand(1);
  CLI::App* dir = cmd->add_subcommand("dir", "Print the cache directory (CLPT_CACHE_DIR, else "
                                             "$XDG_CACHE_HOME/clpt/kernels, else ~/.cache/clpt/kernels)");
  cmd->add_subcommand("clear", "Remove every cached kernel binary (*.bin) and print how many");
  return [dir] {
    KernelCache cache(KernelCache::default_dir());
    if (cache.dir().empty())
      throw Error(ExitCode::Usage, "no kernel cache directory: set CLPT_CACHE_DIR, XDG_CACHE_HOME or HOME");
    if (*dir) {
      std::printf("%s\n", cache.dir().c_str());
      return 0;
    }
    const size_t removed = cache.clear();
    std::printf("removed %zu kernel cache entr%s from %s\n", removed, removed == 1 ? "y" : "ies",
                cache.dir().c_str());
    return 0;
  };
}

}  // namespace clpt
