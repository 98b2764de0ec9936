// The glTF node hierarchy (glTF 2.0 section 3.5): each node's local transform (`matrix`, or
// translation x rotation x scale) checked and composed down the tree into world transforms, the
// tree itself checked (indices in range, no node with two parents, no node its own ancestor, a
// scene's nodes all roots). Affine transforms in double, row-major like scene/mesh_placement.h.
#pragma once

#include "scene/tinygltf_config.h"

#include <vector>

#include "scene/mesh_placement.h"

namespace clpt {

// p -> linear p + translation.
struct Affine {
  Matrix3 linear{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
  Vec3 translation{0, 0, 0};
};

Affine compose(const Affine& outer, const Affine& inner);  // outer after inner
Vec3 transform_point(const Affine& a, const Vec3& p);
Vec3 transform_vector(const Affine& a, const Vec3& v);
// The inverse transpose of the linear part applied to n (not normalised): a normal's transform.
Vec3 transform_normal(const Affine& a, const Vec3& n);
double determinant(const Matrix3& m);
// A [[mesh]]-style placement (scale, rotate_deg, translate) as an Affine.
Affine placement_affine(const MeshPlacement& placement);

// nodes[index]'s local transform; throws GltfError naming the node's property at fault (matrix
// and TRS together, wrong lengths, NaN or Inf, a matrix whose last row is not 0 0 0 1, a singular
// matrix or a zero scale, a quaternion whose length is not 1 within 1e-5).
Affine node_transform(const tinygltf::Model& model, int index);

// The scene to render: `scene`, else scenes[0]; throws when there is none or `scene` is out of
// range.
int chosen_scene(const tinygltf::Model& model);

struct NodeInstance {
  int node;
  Affine world;  // root x the transforms of the node's ancestors x its own
};

// Every node of scenes[scene], depth first (the scene's nodes in order, each node's children in
// order), with its world transform. Checks the whole node graph first: children in range, no
// node with two parents, no node its own ancestor, the scene's nodes in range, roots, listed once.
std::vector<NodeInstance> scene_nodes(const tinygltf::Model& model, int scene, const Affine& root);

}  // namespace clpt
