// What the mesh-file fuzzers (fuzz_mesh_file, fuzz_assimp_mesh) demand of a mesh clpt accepted:
// LocalMesh's contract (mesh_placement.h) before placement and finite unit normals after it.
// A breach aborts with the harness's name, so libFuzzer keeps the input as a crash.
#pragma once

#include "scene/mesh_placement.h"

namespace clpt_fuzz {

[[noreturn]] void finding(const char* harness, const char* what);

// Checks `mesh` as parse_mesh_file / mesh_from_assimp returned it, places it as a scene may
// (non-uniform scale, rotation) and checks the placed normals.
void check_accepted_mesh(const char* harness, const clpt::LocalMesh& mesh);

}  // namespace clpt_fuzz
