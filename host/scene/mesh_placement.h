// Placing a mesh's vertices in the world (scene.h MeshPlacement: scale per axis, then rotate
// about x, y, z, then translate) and turning placed triangles into the TriangleMesh the BVH
// consumes: normals carried along, degenerate triangles dropped.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace clpt {

// The placement's linear part as a row-major 3x3 matrix: Rz Ry Rx diag(scale).
using Matrix3 = std::array<std::array<double, 3>, 3>;
Matrix3 placement_matrix(const MeshPlacement& placement);

// translate + Rz Ry Rx (scale * p).
Vec3 place_point(const MeshPlacement& placement, const Vec3& p);

// The unit world normal of a surface whose local unit normal is n: Rz Ry Rx (n / scale),
// normalised (the inverse transpose of the linear part; a non-uniform scale tilts normals).
Vec3 place_normal(const MeshPlacement& placement, const Vec3& n);

// Vertices, optional per-vertex normals (empty or one per vertex; need not be unit length but
// not zero) and triangles with indices already checked to be in range, before placement.
struct LocalMesh {
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;
  std::vector<std::array<double, 2>> uvs;  // empty, or one per vertex (OBJ's convention, scene.h)
  std::vector<std::array<uint32_t, 3>> triangles;
};

// `mesh`'s positions, normals and triangles set from `local` placed by mesh.placement; triangles
// of zero area in double after placement are dropped. Returns how many were dropped.
size_t place_mesh(const LocalMesh& local, TriangleMesh& mesh);

}  // namespace clpt
