// glTF mesh primitives (glTF 2.0 section 3.7.2) as clpt's world-space TriangleMeshes: one per
// primitive per node that places its mesh (a mesh used by two nodes is two placements).
// Triangles, strips and fans, indexed or not; positions and normals through the node's world
// transform (normals by its inverse transpose), the winding reversed where that transform
// mirrors, so that faces stay outward; degenerate triangles dropped as [[mesh]] drops them
// (scene/mesh_placement.h place_mesh). Points and lines are skipped: clpt renders surfaces.
#pragma once

#include "scene/tinygltf_config.h"

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include "scene/gltf_nodes.h"
#include "scene/scene.h"

namespace clpt {

struct PrimitiveContext {
  const tinygltf::Model& model;
  const std::vector<Material>& materials;  // the file's materials, converted (gltf_material.h)
  uint64_t total_bytes;                    // GltfDocument::total_bytes
  std::set<std::string> skipped_modes;     // POINTS, LINES ... met so far (one warning names them)
  std::vector<std::string> warnings;       // "ELEMENT: MESSAGE"
  uint64_t triangles = 0;                  // placed so far, against kMaxGltfTriangles
};

// Instancing multiplies a file's triangles by its placements, so a small file could ask for any
// number: the placed triangles may not exceed this (render/limits.h kMaxTriangles, the most a
// render takes; the scene layer cannot include the render layer's header).
constexpr uint64_t kMaxGltfTriangles = uint64_t(1) << 27;

// The TriangleMeshes of the mesh that `instance`'s node places (none if it places none), appended
// to `out`. Each is named "MESH/primitive P" (MESH: the mesh's name, else "meshes[M]"), with
// gltf_element "nodes[N] meshes[M].primitives[P]" and the primitive's material (the
// specification's default material when it has none).
void append_node_meshes(PrimitiveContext& context, const NodeInstance& instance, std::vector<TriangleMesh>& out);

}  // namespace clpt
