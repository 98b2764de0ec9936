#include "util/module_loader.h"

#include <dlfcn.h>

#include <cstdlib>
#include <filesystem>

namespace clpt {

std::vector<std::string> module_candidates(const char* env_var, const char* file_name, const char* built_path) {
  if (const char* env = std::getenv(env_var); env && *env) return {env};
  std::vector<std::string> paths;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) paths.push_back((exe.parent_path() / file_name).string());
  if (built_path) paths.emplace_back(built_path);
  return paths;
}

LoadedModule load_module(const std::vector<std::string>& candidates, const char* entry_symbol, int dlopen_flags) {
  LoadedModule result;
  for (const std::string& path : candidates) {
    if (!std::filesystem::exists(path)) {
      result.tried += "\n  " + path + ": no such file";
      continue;
    }
    void* handle = dlopen(path.c_str(), dlopen_flags);
    if (!handle) {
      result.tried += "\n  " + path + ": " + dlerror();
      continue;
    }
    void* entry = dlsym(handle, entry_symbol);
    if (!entry) {
      result.tried += "\n  " + path + ": no " + entry_symbol + " (a module from another clpt version?)";
      continue;
    }
    result.entry = entry;
    result.tried.clear();
    return result;
  }
  return result;
}

}  // namespace clpt
