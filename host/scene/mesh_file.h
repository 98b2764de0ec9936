// Mesh files (OBJ, PLY, glTF binary, STL) read through assimp: with scene/assimp_mesh.h (the
// checks and conversion of what assimp returns), the only files in clpt that see assimp's
// types. What comes back is plain vertices and triangles (scene/mesh_placement.h LocalMesh)
// that clpt has checked itself: finite positions, non-zero normals, indices in range.
// The loader (scene_loader.cpp) adds the [[mesh]] table's position to every message.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "scene/mesh_placement.h"

namespace clpt {

// A mesh file clpt cannot use. The message names the problem and, where known, the element
// ("vertex 12 of mesh 0"), but not the file: the caller knows how the scene names it.
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Mesh files larger than this are refused before assimp reads them (and before clpt reads them
// into memory): 1 GiB, far above any mesh whose indices fit the 32-bit triangles of scene.h.
constexpr uint64_t kMaxMeshFileBytes = uint64_t(1) << 30;

// The extensions accepted (lower case, without the dot), in the order messages list them.
const std::vector<std::string>& mesh_file_extensions();

// The lower-case extension of `path` if it is one of mesh_file_extensions(); otherwise throws
// MeshFileError naming the accepted ones.
std::string mesh_file_extension(const std::string& path);

// `mesh_file` as a [[mesh]] table names it, resolved against the directory of the scene file
// `scene_file` (absolute names stay as they are).
std::string resolve_mesh_path(const std::string& scene_file, const std::string& mesh_file);

// The file's bytes, after checking that it exists, is a regular file and is at most
// kMaxMeshFileBytes long; throws MeshFileError otherwise.
std::string read_mesh_file(const std::string& path);

struct MeshFileContents {
  LocalMesh mesh;                     // all of the file's triangle meshes, merged
  std::vector<std::string> warnings;  // e.g. lines and points skipped, normals ignored
};

// Parses `bytes` as a mesh file of type `extension` (one of mesh_file_extensions()) and merges
// every triangle mesh in it, node transforms applied, into one LocalMesh. Normals are kept when
// every merged mesh has them (never generated). Throws MeshFileError with assimp's own message
// when assimp refuses the file, and with the element when a vertex is not finite, a normal is
// zero or not finite, or nothing triangular is left. Self-contained files only: the bytes are
// all assimp sees (an OBJ's .mtl or a .gltf's external buffers are not opened; clpt's materials
// come from the scene), so the scene hash over these bytes covers everything the mesh depends on.
MeshFileContents parse_mesh_file(std::string_view bytes, const std::string& extension);

}  // namespace clpt
