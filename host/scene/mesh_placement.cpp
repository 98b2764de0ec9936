// Mesh placement: the matrices of scene.h MeshPlacement and the placed TriangleMesh.
#include "scene/mesh_placement.h"

#include <cmath>

#include "scene/vec3_ops.h"

namespace clpt {
namespace {

Matrix3 multiply(const Matrix3& a, const Matrix3& b) {
  Matrix3 out{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) out[i][j] += a[i][k] * b[k][j];
  return out;
}

Vec3 multiply(const Matrix3& m, const Vec3& v) {
  return {dot(Vec3{m[0][0], m[0][1], m[0][2]}, v), dot(Vec3{m[1][0], m[1][1], m[1][2]}, v),
          dot(Vec3{m[2][0], m[2][1], m[2][2]}, v)};
}

// Right-handed rotation by `degrees` about coordinate axis `axis` (0 x, 1 y, 2 z).
Matrix3 rotation(int axis, double degrees) {
  const double pi = 3.14159265358979323846;
  const double c = std::cos(degrees * pi / 180), s = std::sin(degrees * pi / 180);
  const int a = (axis + 1) % 3, b = (axis + 2) % 3;  // the plane rotated: a towards b
  Matrix3 m{};
  m[axis][axis] = 1;
  m[a][a] = c;
  m[a][b] = -s;
  m[b][a] = s;
  m[b][b] = c;
  return m;
}

Matrix3 rotation_xyz(const Vec3& degrees) {
  return multiply(rotation(2, degrees[2]), multiply(rotation(1, degrees[1]), rotation(0, degrees[0])));
}

// The inverse transpose of rotate * diag(scale) applied to n, normalised.
Vec3 normal_with(const Matrix3& rotate, const Vec3& scale, const Vec3& n) {
  return normalize(multiply(rotate, Vec3{n[0] / scale[0], n[1] / scale[1], n[2] / scale[2]}));
}

}  // namespace

Matrix3 placement_matrix(const MeshPlacement& placement) {
  Matrix3 scale{};
  for (int i = 0; i < 3; ++i) scale[i][i] = placement.scale[i];
  return multiply(rotation_xyz(placement.rotate_deg), scale);
}

Vec3 place_point(const MeshPlacement& placement, const Vec3& p) {
  return add(multiply(placement_matrix(placement), p), placement.translate);
}

Vec3 place_normal(const MeshPlacement& placement, const Vec3& n) {
  return normal_with(rotation_xyz(placement.rotate_deg), placement.scale, n);
}

size_t place_mesh(const LocalMesh& local, TriangleMesh& mesh) {
  const Matrix3 linear = placement_matrix(mesh.placement);
  const Matrix3 rotate = rotation_xyz(mesh.placement.rotate_deg);
  mesh.positions.clear();
  mesh.normals.clear();
  mesh.triangles.clear();
  mesh.positions.reserve(local.positions.size());
  for (const Vec3& p : local.positions) mesh.positions.push_back(add(multiply(linear, p), mesh.placement.translate));
  mesh.normals.reserve(local.normals.size());
  for (const Vec3& n : local.normals)
    mesh.normals.push_back(normal_with(rotate, mesh.placement.scale, n));
  if (!local.uvs.empty()) mesh.uvs = local.uvs;  // a glTF primitive sets mesh.uvs itself
  size_t dropped = 0;
  mesh.triangles.reserve(local.triangles.size());
  for (const auto& t : local.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const Vec3 area2 = cross(sub(mesh.positions[t[1]], a), sub(mesh.positions[t[2]], a));
    if (length(area2) > 0) {
      mesh.triangles.push_back(t);
    } else {
      ++dropped;
    }
  }
  return dropped;
}

}  // namespace clpt
