// What clpt does with what assimp returns: the checks on an aiScene's meshes (finite vertices,
// usable normals) and their conversion into one LocalMesh (indices in range, points, lines and
// polygons skipped and counted, normals kept only when every triangle mesh has them). Split from
// mesh_file.cpp so that tests/fuzz/fuzz_assimp_mesh.cpp can drive it with synthetic aiScenes at
// thousands of inputs a second, where assimp's parsers manage 5 to 130 (docs/testing.md).
// Contract on the input: what assimp's aiProcess_ValidateDataStructure guarantees and no more:
// mMeshes holds mNumMeshes non-null meshes, each mVertices (and mNormals when HasNormals())
// holds mNumVertices entries, mFaces holds mNumFaces faces whose mIndices hold mNumIndices
// values each. Index values, arities, counts and float values are all checked here.
#pragma once

#include <assimp/scene.h>

#include "scene/mesh_file.h"

namespace clpt {

// Sets every mesh's mPrimitiveTypes to the arities its faces really have, before assimp's
// triangulation runs. Debian's assimp 5.2 is built with assertions on, and its triangulation
// aborts the process (ai_assert numOut != pMesh->mNumFaces, TriangulateProcess.cpp:238) on a mesh
// that declares polygons but has none, as some malformed PLY files make its reader declare
// (found by tests/fuzz/fuzz_mesh_file; README "Known library crashes and leaks"). Throws
// MeshFileError naming the face ("face 3 of mesh 0") for a face without indices.
void declare_primitive_types(aiScene& scene);

// Throws MeshFileError naming the element ("vertex 12 of mesh 0") when a vertex is not finite or
// a normal is zero or not finite. Run before assimp joins identical vertices, which would merge
// a NaN vertex into another one unseen.
void check_assimp_vertices(const aiScene& scene);

// Every triangle mesh of `scene` merged into one LocalMesh, vertices renumbered; warnings for
// skipped faces and ignored normals. Throws MeshFileError when a face's index is out of range,
// when the merged mesh would need more than 32-bit indices, or when no triangle is left.
MeshFileContents mesh_from_assimp(const aiScene& scene);

}  // namespace clpt
