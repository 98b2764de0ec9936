#include "tools/gnuplot.h"

#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <sstream>

#include "util/atomic_file.h"
#include "util/error.h"

extern char** environ;

namespace clpt {
namespace {

// Runs `gnuplot script_path` and waits. Returns "" on success, else why it failed.
std::string run_gnuplot(const std::string& gnuplot, const std::string& script_path) {
  std::string arg0 = "gnuplot", arg1 = script_path;
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int spawn_error = ::posix_spawn(&pid, gnuplot.c_str(), nullptr, nullptr, argv, environ);
  if (spawn_error != 0) return "cannot start " + gnuplot + ": " + std::strerror(spawn_error);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return std::string("waiting for gnuplot failed: ") + std::strerror(errno);
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  if (WIFSIGNALED(status)) return "gnuplot was killed by signal " + std::to_string(WTERMSIG(status));
  return "gnuplot exited with status " + std::to_string(WEXITSTATUS(status)) + " (its messages are above)";
}

}  // namespace

std::string find_gnuplot() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    if (dir.empty()) continue;
    const std::filesystem::path candidate = std::filesystem::path(dir) / "gnuplot";
    std::error_code ec;
    if (std::filesystem::is_regular_file(candidate, ec) && ::access(candidate.c_str(), X_OK) == 0)
      return candidate.string();
  }
  return "";
}

void write_gnuplot_png(const std::string& gnuplot, const std::string& option, const std::string& png_path,
                       const std::function<std::string(const std::string& tmp)>& script_for) {
  const std::string tmp_png = temporary_path_for(png_path);
  const std::string tmp_script = temporary_path_for(png_path + ".gp");
  write_file_atomically(tmp_script, script_for(tmp_png), option);
  const std::string failure = run_gnuplot(gnuplot, tmp_script);
  std::remove(tmp_script.c_str());
  std::error_code ec;
  if (failure.empty() && std::filesystem::file_size(tmp_png, ec) > 0 && !ec) {
    commit_temporary(tmp_png, png_path);
    return;
  }
  std::remove(tmp_png.c_str());
  throw Error(ExitCode::OutputError, option + " " + png_path + ": cannot draw the plot: " +
                                         (failure.empty() ? "gnuplot wrote no image" : failure));
}

}  // namespace clpt
