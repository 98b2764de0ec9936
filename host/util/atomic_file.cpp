#include "util/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "util/error.h"

namespace clpt {

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
