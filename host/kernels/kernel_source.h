// Kernel sources are embedded in the binary at build time (cmake/embed_kernels.cmake), so clpt
// never reads kernels relative to the working directory. A program's source is assembled from an
// entry file by expanding `#include "file"` from the embedded set, each file once, with `#line`
// markers so that build logs name the real file and line.
#pragma once

#include <string>
#include <vector>

namespace clpt {

struct EmbeddedFile {
  const char* name;  // file name, e.g. "megakernel.cl"
  const char* text;  // its contents
};

// Every file under kernels/ and tests/kernels/ (generated).
const std::vector<EmbeddedFile>& embedded_kernel_files();

// Full source of `entry_file` with its includes expanded. Throws Error(Failure) for an unknown file.
std::string assemble_kernel_source(const std::string& entry_file);

}  // namespace clpt
