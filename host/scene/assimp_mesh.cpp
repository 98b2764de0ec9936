// clpt's checks on, and conversion of, the meshes assimp returns (assimp_mesh.h): nothing here
// parses a file, so the fuzzer of synthetic aiScenes (tests/fuzz/fuzz_assimp_mesh.cpp) reaches
// every line of it.
#include "scene/assimp_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace clpt {
namespace {

std::string vec3_text(const aiVector3D& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "[%.9g, %.9g, %.9g]", double(v.x), double(v.y), double(v.z));
  return buffer;
}

bool finite(const aiVector3D& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string element(const char* what, size_t index, unsigned mesh) {
  return std::string(what) + " " + std::to_string(index) + " of mesh " + std::to_string(mesh);
}

size_t faces_with(const aiMesh& m, bool (*arity)(unsigned)) {
  return size_t(std::count_if(m.mFaces, m.mFaces + m.mNumFaces, [&](const aiFace& f) { return arity(f.mNumIndices); }));
}
bool triangle(unsigned n) { return n == 3; }
bool point_or_line(unsigned n) { return n < 3; }

// Appends one assimp mesh's triangles and vertices to `out` (vertices renumbered after those
// already there); `with_normals` says whether the merged mesh keeps normals. Faces of other
// arities are left out: the caller counts them.
void append_mesh(const aiMesh& m, unsigned index, bool with_normals, bool with_uvs, LocalMesh& out) {
  const size_t base = out.positions.size();
  if (base + m.mNumVertices > std::numeric_limits<uint32_t>::max())
    throw MeshFileError("more than 2^32 - 1 vertices (clpt's triangles index vertices with 32 bits)");
  for (unsigned v = 0; v < m.mNumVertices; ++v) {
    const aiVector3D& p = m.mVertices[v];
    out.positions.push_back({double(p.x), double(p.y), double(p.z)});
    if (with_normals) out.normals.push_back({double(m.mNormals[v].x), double(m.mNormals[v].y), double(m.mNormals[v].z)});
    if (with_uvs) {
      // assimp's coordinates are OBJ's ((0, 0) at the image's bottom-left; its glTF reader flips v).
      const aiVector3D& uv = m.mTextureCoords[0][v];
      if (!std::isfinite(uv.x) || !std::isfinite(uv.y))
        throw MeshFileError(element("texture coordinate", v, index) + " is not finite");
      out.uvs.push_back({double(uv.x), double(uv.y)});
    }
  }
  for (unsigned f = 0; f < m.mNumFaces; ++f) {
    const aiFace& face = m.mFaces[f];
    if (face.mNumIndices != 3) continue;
    std::array<uint32_t, 3> t{};
    for (int k = 0; k < 3; ++k) {
      // assimp's validation checks indices too; this keeps clpt safe should a version not.
      if (face.mIndices[k] >= m.mNumVertices)
        throw MeshFileError(element("face", f, index) + " uses vertex " + std::to_string(face.mIndices[k]) +
                            " of " + std::to_string(m.mNumVertices));
      t[size_t(k)] = static_cast<uint32_t>(base + face.mIndices[k]);
    }
    out.triangles.push_back(t);
  }
}

// aiPrimitiveType of a face of `n` indices (none for an empty face).
unsigned primitive_type(unsigned n) {
  if (n == 0) return 0;
  if (n > 3) return aiPrimitiveType_POLYGON;
  return n == 1 ? unsigned(aiPrimitiveType_POINT) : n == 2 ? unsigned(aiPrimitiveType_LINE) : unsigned(aiPrimitiveType_TRIANGLE);
}

}  // namespace

void declare_primitive_types(aiScene& scene) {
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    aiMesh& m = *scene.mMeshes[i];
    unsigned types = 0;
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      // A mesh of empty faces declares no type, and assimp's triangulation then counts every face
      // that is not a triangle as one to split and fails the same assertion (a PLY face list of
      // count 0; found by fuzz_mesh_file on 2026-12-03).
      if (m.mFaces[f].mNumIndices == 0) throw MeshFileError(element("face", f, i) + " has no vertex indices");
      types |= primitive_type(m.mFaces[f].mNumIndices);
    }
    m.mPrimitiveTypes = types;
  }
}

void check_assimp_vertices(const aiScene& scene) {
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    for (unsigned v = 0; v < m.mNumVertices; ++v) {
      if (!finite(m.mVertices[v]))
        throw MeshFileError(element("vertex", v, i) + " is not finite (got " + vec3_text(m.mVertices[v]) + ")");
      if (!m.HasNormals()) continue;
      const aiVector3D& n = m.mNormals[v];
      if (!finite(n) || (n.x == 0 && n.y == 0 && n.z == 0))
        throw MeshFileError(element("normal", v, i) + " is zero or not finite (got " + vec3_text(n) + ")");
    }
  }
}

MeshFileContents mesh_from_assimp(const aiScene& scene) {
  MeshFileContents out;
  std::vector<unsigned> triangle_meshes;
  size_t points_and_lines = 0, polygons = 0;
  for (unsigned i = 0; i < scene.mNumMeshes; ++i) {
    const aiMesh& m = *scene.mMeshes[i];
    const size_t triangles = faces_with(m, triangle), small = faces_with(m, point_or_line);
    points_and_lines += small;
    polygons += m.mNumFaces - triangles - small;
    if (triangles > 0) triangle_meshes.push_back(i);
  }
  if (points_and_lines > 0)
    out.warnings.push_back(std::to_string(points_and_lines) + " point or line primitive(s) skipped (only triangles render)");
  // aiProcess_Triangulate leaves none; counted rather than assumed (found by fuzz_assimp_mesh,
  // where the warning above used to call them points or lines).
  if (polygons > 0)
    out.warnings.push_back(std::to_string(polygons) + " face(s) of more than 3 vertices skipped (not triangulated)");
  const auto has_normals = [&](unsigned i) { return scene.mMeshes[i]->HasNormals(); };
  const bool with_normals =
      !triangle_meshes.empty() && std::all_of(triangle_meshes.begin(), triangle_meshes.end(), has_normals);
  if (!with_normals && std::any_of(triangle_meshes.begin(), triangle_meshes.end(), has_normals))
    out.warnings.push_back("normals ignored: only some of the file's meshes have them (geometric normals shade)");
  // Texture coordinates (the first set) likewise only when every merged mesh has them.
  const auto has_uvs = [&](unsigned i) { return scene.mMeshes[i]->HasTextureCoords(0); };
  const bool with_uvs = !triangle_meshes.empty() && std::all_of(triangle_meshes.begin(), triangle_meshes.end(), has_uvs);
  if (!with_uvs && std::any_of(triangle_meshes.begin(), triangle_meshes.end(), has_uvs))
    out.warnings.push_back("texture coordinates ignored: only some of the file's meshes have them");
  for (unsigned i : triangle_meshes) append_mesh(*scene.mMeshes[i], i, with_normals, with_uvs, out.mesh);
  if (out.mesh.triangles.empty()) throw MeshFileError("the mesh file has no triangles");
  return out;
}

}  // namespace clpt
