// libFuzzer harness for what clpt does with what assimp returns (scene/assimp_mesh.h), without
// assimp's parsers: the input is decoded into a synthetic aiScene -- up to 8 meshes of up to 64
// vertices (each coordinate an arbitrary float or one of NaN, +-Inf, 0, -0, the smallest
// denormal, FLT_MAX), normals present or not, up to 64 faces of 0 to 5 indices each, the indices
// either in range or any 32-bit value, any declared primitive types -- which goes through
// declare_primitive_types (after which the declared types must be exactly the faces' own),
// check_assimp_vertices and mesh_from_assimp as parse_mesh_file sends assimp's scene, and an accepted mesh through
// placement (mesh_contract.h). MeshFileError is the normal refusal; another exception, a crash,
// a sanitizer report or a broken contract is a finding. The aiScene honours what assimp's
// validation guarantees (assimp_mesh.h) and nothing more.
#include <fuzzer/FuzzedDataProvider.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <exception>
#include <limits>
#include <memory>

#include "mesh_contract.h"
#include "scene/assimp_mesh.h"

namespace {

constexpr const char* kHarness = "fuzz_assimp_mesh";

float coordinate(FuzzedDataProvider& in) {
  constexpr float kSpecial[] = {std::numeric_limits<float>::quiet_NaN(), INFINITY, -INFINITY, 0.0f, -0.0f,
                                std::numeric_limits<float>::denorm_min(), FLT_MAX, -FLT_MAX};
  constexpr int kCount = int(sizeof kSpecial / sizeof kSpecial[0]);
  const int pick = in.ConsumeIntegralInRange<int>(0, 4 * kCount);
  if (pick < kCount) return kSpecial[pick];
  if (pick < 2 * kCount) return in.ConsumeFloatingPoint<float>();
  return float(in.ConsumeIntegralInRange<int>(-4, 4));  // small integers: shared and degenerate vertices
}

aiVector3D vector(FuzzedDataProvider& in) {
  const float x = coordinate(in), y = coordinate(in);
  return {x, y, coordinate(in)};
}

// One mesh as aiMesh's destructor expects to free it (new[] arrays).
aiMesh* decode_mesh(FuzzedDataProvider& in) {
  auto mesh = std::make_unique<aiMesh>();
  mesh->mPrimitiveTypes = in.ConsumeIntegralInRange<unsigned>(0, 15);  // what a reader may have claimed
  mesh->mNumVertices = in.ConsumeIntegralInRange<unsigned>(0, 64);
  const bool normals = in.ConsumeBool();
  if (mesh->mNumVertices > 0) {
    mesh->mVertices = new aiVector3D[mesh->mNumVertices];
    for (unsigned v = 0; v < mesh->mNumVertices; ++v) mesh->mVertices[v] = vector(in);
    if (normals) {
      mesh->mNormals = new aiVector3D[mesh->mNumVertices];
      for (unsigned v = 0; v < mesh->mNumVertices; ++v) mesh->mNormals[v] = vector(in);
    }
  }
  mesh->mNumFaces = in.ConsumeIntegralInRange<unsigned>(0, 64);
  if (mesh->mNumFaces > 0) mesh->mFaces = new aiFace[mesh->mNumFaces];
  for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
    aiFace& face = mesh->mFaces[f];
    face.mNumIndices = in.ConsumeIntegralInRange<unsigned>(0, 5);
    if (face.mNumIndices == 0) continue;
    face.mIndices = new unsigned[face.mNumIndices];
    for (unsigned k = 0; k < face.mNumIndices; ++k)
      face.mIndices[k] = in.ConsumeBool() ? in.ConsumeIntegral<unsigned>()
                                          : in.ConsumeIntegralInRange<unsigned>(0, mesh->mNumVertices);
  }
  return mesh.release();
}

// After declare_primitive_types: a type is declared if and only if a face of that arity exists.
void check_declared_types(const aiScene& scene) {
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    unsigned seen = 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      const unsigned n = m.mFaces[f].mNumIndices;
      if (n >= 4) seen |= aiPrimitiveType_POLYGON;
      if (n == 3) seen |= aiPrimitiveType_TRIANGLE;
      if (n == 2) seen |= aiPrimitiveType_LINE;
      if (n == 1) seen |= aiPrimitiveType_POINT;
    }
    if (seen != m.mPrimitiveTypes) clpt_fuzz::finding(kHarness, "declared primitive types differ from the faces'");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  aiScene scene;  // its destructor frees the meshes
  scene.mNumMeshes = in.ConsumeIntegralInRange<unsigned>(0, 8);
  if (scene.mNumMeshes > 0) {
    scene.mMeshes = new aiMesh*[scene.mNumMeshes];
    for (unsigned i = 0; i < scene.mNumMeshes; ++i) scene.mMeshes[i] = decode_mesh(in);
  }
  try {
    clpt::declare_primitive_types(scene);
    check_declared_types(scene);
    clpt::check_assimp_vertices(scene);
    const clpt::MeshFileContents contents = clpt::mesh_from_assimp(scene);
    clpt_fuzz::check_accepted_mesh(kHarness, contents.mesh);
  } catch (const clpt::MeshFileError&) {
    // Refused, with a message: the normal outcome for many inputs.
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", kHarness, e.what());
    clpt_fuzz::finding(kHarness, "a std::exception other than MeshFileError");
  } catch (...) {
    clpt_fuzz::finding(kHarness, "a non-standard exception");
  }
  return 0;
}
