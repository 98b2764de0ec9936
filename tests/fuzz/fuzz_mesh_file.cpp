// libFuzzer harness for mesh files through clpt's loading path: the first byte picks the file type
// (mesh_file_extensions(), modulo their count), the rest is the file's bytes, which go to
// clpt::parse_mesh_file (assimp from memory, then clpt's checks) and the result to place_mesh
// (placement, degenerate triangles dropped; mesh_contract.h), as the scene loader does.
// Refusing the input with MeshFileError is the normal outcome; anything else -- another exception, a crash, a sanitizer
// report in clpt's code, or a result that breaks LocalMesh's contract -- is a finding.
// assimp itself is Debian's uninstrumented build: coverage guides through clpt's code only, and
// a crash inside assimp shows as a plain SEGV (README "Known library crashes and leaks").
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <string>
#include <string_view>

#include "mesh_contract.h"
#include "scene/mesh_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const auto& extensions = clpt::mesh_file_extensions();
  const std::string& extension = extensions[data[0] % extensions.size()];
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const clpt::MeshFileContents contents = clpt::parse_mesh_file(bytes, extension);
    clpt_fuzz::check_accepted_mesh("fuzz_mesh_file", contents.mesh);
  } catch (const clpt::MeshFileError&) {
    // Refused, with a message: the normal outcome for most inputs.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_mesh_file: %s\n", e.what());
    clpt_fuzz::finding("fuzz_mesh_file", "a std::exception other than MeshFileError");
  } catch (...) {
    clpt_fuzz::finding("fuzz_mesh_file", "a non-standard exception");
  }
  return 0;
}
