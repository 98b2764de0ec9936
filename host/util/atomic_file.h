// Atomic output: every file clpt writes (images, films, checkpoints, kernel cache entries, JSON)
// is written under a temporary name in the same directory and renamed into place, so a failed,
// interrupted or concurrent run never leaves a half-written file under the requested name.
#pragma once

#include <filesystem>
#include <string>

namespace clpt {

// The directory a file named `path` goes in: its parent, or "." for a bare name such as
// "out.exr" (whose parent_path() is empty, which std::filesystem::absolute and relative reject).
std::filesystem::path directory_of(const std::string& path);

// Checks, before any work, that an output file can be written at `path` (given with `option`,
// e.g. "-o"): its directory exists, is a directory and takes a new file (a temporary file is made
// there and removed), and `path` is not a directory. Throws Error(OutputError) naming the option,
// the path and why not.
void check_output_file(const std::string& option, const std::string& path);

// The same for an output directory that files will be written into (`kernels emit DIR`,
// `verify --save-reference-films DIR`): it exists, is a directory and takes a new file.
void check_output_directory(const std::string& option, const std::string& dir);

// ".STEM.clpt-tmp-PID.EXT" beside `path`: same directory (rename stays on one file system) and
// same extension (image writers pick the format from it).
std::string temporary_path_for(const std::string& path);

// Renames tmp to path, or removes tmp and throws Error(OutputError) naming `path`.
void commit_temporary(const std::string& tmp, const std::string& path);

// Writes `bytes` to `path` atomically; throws Error(OutputError) naming `what` and `path`.
void write_file_atomically(const std::string& path, const std::string& bytes, const std::string& what);

}  // namespace clpt
