// Modules that clpt loads at run time with dlopen (the image I/O module, host/io/image_codec.h;
// the MPI module, host/render/rank_group.h): where each may be, and loading one to its entry
// point. A module is a build product beside the clpt executable, so the places are the same for
// every module.
#pragma once

#include <string>
#include <vector>

namespace clpt {

// Where the module `file_name` may be: $`env_var` when set (then nowhere else); otherwise beside
// the running executable (the build directory's clpt), then `built_path`, where CMake built it
// (test executables live elsewhere; null: none).
std::vector<std::string> module_candidates(const char* env_var, const char* file_name, const char* built_path);

struct LoadedModule {
  void* entry = nullptr;  // the address of the entry point; null on failure
  std::string tried;      // on failure: one line per candidate and why it failed
};

// The first candidate that exists, loads with `dlopen_flags` and has `entry_symbol`. The module
// stays loaded until the process ends.
LoadedModule load_module(const std::vector<std::string>& candidates, const char* entry_symbol, int dlopen_flags);

}  // namespace clpt
