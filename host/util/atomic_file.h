// Atomic output: every file clpt writes (images, films, checkpoints, kernel cache entries, JSON)
// is written under a temporary name in the same directory and renamed into place, so a failed,
// interrupted or concurrent run never leaves a half-written file under the requested name.
#pragma once

#include <string>

namespace clpt {

// ".STEM.clpt-tmp-PID.EXT" beside `path`: same directory (rename stays on one file system) and
// same extension (image writers pick the format from it).
std::string temporary_path_for(const std::string& path);

// Renames tmp to path, or removes tmp and throws Error(OutputError) naming `path`.
void commit_temporary(const std::string& tmp, const std::string& path);

// Writes `bytes` to `path` atomically; throws Error(OutputError) naming `what` and `path`.
void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what);

}  // namespace clpt
