// The mesh fuzzers' shared acceptance checks (mesh_contract.h).
#include "mesh_contract.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace clpt_fuzz {

void finding(const char* harness, const char* what) {
  std::fprintf(stderr, "%s: %s\n", harness, what);
  std::abort();  // libFuzzer saves the input as a crash
}

void check_accepted_mesh(const char* harness, const clpt::LocalMesh& mesh) {
  if (mesh.triangles.empty()) finding(harness, "an accepted mesh has no triangles");
  if (!mesh.normals.empty() && mesh.normals.size() != mesh.positions.size())
    finding(harness, "normals are neither empty nor one per vertex");
  for (const auto& t : mesh.triangles)
    for (uint32_t i : t)
      if (i >= mesh.positions.size()) finding(harness, "a triangle index is out of range");
  for (const auto& p : mesh.positions)
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) finding(harness, "a vertex is not finite");
  clpt::TriangleMesh placed;
  placed.placement.scale = {2, 0.5, 1};
  placed.placement.rotate_deg = {10, 20, 30};
  const size_t dropped = clpt::place_mesh(mesh, placed);
  if (dropped + placed.triangles.size() != mesh.triangles.size())
    finding(harness, "placement lost triangles it did not count as dropped");
  for (const auto& n : placed.normals) {
    if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) finding(harness, "a placed normal is not finite");
    if (std::abs(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1) > 1e-9)
      finding(harness, "a placed normal is not of unit length");
  }
}

}  // namespace clpt_fuzz
