// libFuzzer harness for mesh files through clpt's loading path: the first byte picks the file type
// (mesh_file_extensions(), modulo their count), the rest is the file's bytes, which go to
// clpt::parse_mesh_file (assimp from memory, then clpt's checks) and the result to place_mesh
// (placement, degenerate triangles dropped), as the scene loader does. Refusing the input with
// MeshFileError is the normal outcome; anything else -- another exception, a crash, a sanitizer
// report in clpt's code, or a result that breaks LocalMesh's contract -- is a finding.
// assimp itself is Debian's uninstrumented build: coverage guides through clpt's code only, and
// a crash inside assimp shows as a plain SEGV (README "Known library crashes and leaks").
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <string_view>

#include "scene/mesh_file.h"
#include "scene/mesh_placement.h"

namespace {

[[noreturn]] void finding(const char* what) {
  std::fprintf(stderr, "fuzz_mesh_file: %s\n", what);
  std::abort();  // libFuzzer saves the input as a crash
}

void check_contract(const clpt::LocalMesh& mesh) {
  if (mesh.triangles.empty()) finding("an accepted mesh has no triangles");
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    finding("normals are neither empty nor one per vertex");
  for (const auto& t : mesh.triangles)
    for (uint32_t i : t)
      if (i >= mesh.positions.size()) finding("a triangle index is out of range");
  for (const auto& p : mesh.positions)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) finding("a vertex is not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size == 0) return 0;
  const auto& extensions = clpt::mesh_file_extensions();
  const std::string& extension = extensions[data[0] % extensions.size()];
  const std::string_view bytes(reinterpret_cast<const char*>(data + 1), size - 1);
  try {
    const clpt::MeshFileContents contents = clpt::parse_mesh_file(bytes, extension);
    check_contract(contents.mesh);
    clpt::TriangleMesh placed;
    placed.placement.scale = {2, 0.5, 1};
    placed.placement.rotate_deg = {10, 20, 30};
    clpt::place_mesh(contents.mesh, placed);
    for (const auto& n : placed.normals)
      if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) finding("a placed normal is not finite");
  } catch (const clpt::MeshFileError&) {
    // Refused, with a message: the normal outcome for most inputs.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_mesh_file: %s\n", e.what());
    finding("a std::exception other than MeshFileError");
  } catch (...) {
    finding("a non-standard exception");
  }
  return 0;
}
