#include "util/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "util/error.h"

namespace clpt {

std::filesystem::path directory_of(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

namespace {

// `dir` exists, is a directory and takes a new file (named after `probe_for`, then removed); else
// Error(OutputError) beginning with `what`.
void check_directory_takes_files(const std::string& what, const std::filesystem::path& dir,
                                 const std::string& probe_for) {
  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(dir, ec);
  if (!std::filesystem::exists(status))
    throw Error(ExitCode::OutputError, what + "directory '" + dir.string() + "' does not exist");
  if (!std::filesystem::is_directory(status))
    throw Error(ExitCode::OutputError, what + "'" + dir.string() + "' is not a directory");
  const std::string probe = temporary_path_for(probe_for);
  std::FILE* f = std::fopen(probe.c_str(), "wb");
  if (!f)
    throw Error(ExitCode::OutputError,
                what + "cannot create a file in directory '" + dir.string() + "': " + std::strerror(errno));
  std::fclose(f);
  std::remove(probe.c_str());
}

}  // namespace

void check_output_file(const std::string& option, const std::string& path) {
  const std::string what = option + " " + path + ": ";
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(ExitCode::OutputError, what + "a directory of that name exists");
  check_directory_takes_files(what, directory_of(path), path);
}

void check_output_directory(const std::string& option, const std::string& dir) {
  check_directory_takes_files(option + " " + dir + ": ", dir, (std::filesystem::path(dir) / "probe").string());
}

std::string temporary_path_for(const std::string& path) {
  const std::filesystem::path p(path);
  const std::filesystem::path tmp = p.parent_path() / ("." + p.stem().string() + ".clpt-tmp-" +
                                                       std::to_string(::getpid()) + p.extension().string());
  return tmp.string();
}

void commit_temporary(const std::string& tmp, const std::string& path) {
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(tmp.c_str());
    throw Error(ExitCode::OutputError, path + ": cannot write output: " + reason);
  }
}

void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what) {
  const std::string tmp = temporary_path_for(path);
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw Error(ExitCode::OutputError, what + " " + path + ": cannot write file: " + std::strerror(errno));
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  if (std::fclose(f) != 0 || !ok) {
    std::remove(tmp.c_str());
    throw Error(ExitCode::OutputError, what + " " + path + ": cannot write file");
  }
  commit_temporary(tmp, path);
}

}  // namespace clpt
