// Node transforms and the node tree (gltf_nodes.h).
#include "scene/gltf_nodes.h"

#include <cmath>
#include <utility>

#include "scene/gltf_error.h"
#include "scene/vec3_ops.h"

namespace clpt {
namespace {

std::string node_name(int index) { return "nodes[" + std::to_string(index) + "]"; }

void require_finite(const std::vector<double>& values, const std::string& element) {
  for (size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i])) gltf_fail(element, "element " + std::to_string(i) + " is not finite");
}

void require_length(const std::vector<double>& values, size_t length, const std::string& element) {
  if (!values.empty() && values.size() != length)
    gltf_fail(element, "must have " + std::to_string(length) + " numbers (got " + std::to_string(values.size()) + ")");
  require_finite(values, element);
}

// A matrix is singular when its determinant is negligible next to the product of its columns'
// lengths (a scale-free test: a node scaled by 1e-3 is fine, a flattened one is not).
bool singular(const Matrix3& m) {
  double columns = 1;
  for (int c = 0; c < 3; ++c) columns *= length(Vec3{m[0][c], m[1][c], m[2][c]});
  return !(std::fabs(determinant(m)) > 1e-12 * columns) || columns == 0;
}

Affine from_matrix(const std::vector<double>& m, const std::string& element) {
  // Column-major: element (row r, column c) is m[4 c + r].
  if (m[3] != 0 || m[7] != 0 || m[11] != 0 || m[15] != 1)
    gltf_fail(element, "the last row must be 0 0 0 1 (an affine transform)");
  Affine a;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) a.linear[r][c] = m[size_t(4 * c + r)];
    a.translation[r] = m[size_t(12 + r)];
  }
  if (singular(a.linear)) gltf_fail(element, "the matrix is singular");
  return a;
}

// Rotation matrix of the unit quaternion (x, y, z, w).
Matrix3 rotation_matrix(const std::vector<double>& q, const std::string& element) {
  const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(std::fabs(norm - 1) <= 1e-5))
    gltf_fail(element, "a rotation quaternion must have length 1 (got " + std::to_string(norm) + ")");
  const double x = q[0] / norm, y = q[1] / norm, z = q[2] / norm, w = q[3] / norm;
  return {{{1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)},
           {2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)},
           {2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)}}};
}

}  // namespace

Affine compose(const Affine& outer, const Affine& inner) {
  Affine out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      out.linear[r][c] = 0;
      for (int k = 0; k < 3; ++k) out.linear[r][c] += outer.linear[r][k] * inner.linear[k][c];
    }
  out.translation = transform_point(outer, inner.translation);
  return out;
}

Vec3 transform_vector(const Affine& a, const Vec3& v) {
  const Matrix3& m = a.linear;
  return {dot(Vec3{m[0][0], m[0][1], m[0][2]}, v), dot(Vec3{m[1][0], m[1][1], m[1][2]}, v),
          dot(Vec3{m[2][0], m[2][1], m[2][2]}, v)};
}

Vec3 transform_point(const Affine& a, const Vec3& p) { return add(transform_vector(a, p), a.translation); }

Vec3 transform_normal(const Affine& a, const Vec3& n) {
  // The inverse transpose is the cofactor matrix over the determinant; the determinant's sign
  // matters (a mirrored normal must flip with the winding), its size does not.
  const Matrix3& m = a.linear;
  const Vec3 c0{m[0][0], m[1][0], m[2][0]}, c1{m[0][1], m[1][1], m[2][1]}, c2{m[0][2], m[1][2], m[2][2]};
  const Vec3 out = add(add(scale(cross(c1, c2), n[0]), scale(cross(c2, c0), n[1])), scale(cross(c0, c1), n[2]));
  return determinant(m) < 0 ? scale(out, -1) : out;
}

double determinant(const Matrix3& m) {
  return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
         m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

Affine placement_affine(const MeshPlacement& placement) {
  Affine a;
  a.linear = placement_matrix(placement);
  a.translation = placement.translate;
  return a;
}

Affine node_transform(const tinygltf::Model& model, int index) {
  const tinygltf::Node& node = model.nodes[size_t(index)];
  const std::string element = node_name(index);
  require_length(node.matrix, 16, element + ".matrix");
  require_length(node.translation, 3, element + ".translation");
  require_length(node.rotation, 4, element + ".rotation");
  require_length(node.scale, 3, element + ".scale");
  if (!node.matrix.empty()) {
    if (!node.translation.empty() || !node.rotation.empty() || !node.scale.empty())
      gltf_fail(element, "has both 'matrix' and translation, rotation or scale");
    return from_matrix(node.matrix, element + ".matrix");
  }
  Affine a;
  if (!node.rotation.empty()) a.linear = rotation_matrix(node.rotation, element + ".rotation");
  for (size_t i = 0; i < node.scale.size(); ++i) {
    if (node.scale[i] == 0) gltf_fail(element + ".scale", "a zero scale makes the transform singular");
    for (int r = 0; r < 3; ++r) a.linear[r][i] *= node.scale[i];
  }
  if (!node.translation.empty()) a.translation = {node.translation[0], node.translation[1], node.translation[2]};
  return a;
}

int chosen_scene(const tinygltf::Model& model) {
  if (model.scenes.empty()) gltf_fail("scenes", "the file has no scene to render");
  if (model.defaultScene < 0) return 0;
  if (size_t(model.defaultScene) >= model.scenes.size())
    gltf_fail("scene", std::to_string(model.defaultScene) + " is out of range (the file has " +
                           std::to_string(model.scenes.size()) + " scenes)");
  return model.defaultScene;
}

namespace {

// Each node's parent (-1: none), after checking children's indices and that no node has two.
std::vector<int> parents(const tinygltf::Model& model) {
  std::vector<int> parent(model.nodes.size(), -1);
  for (size_t i = 0; i < model.nodes.size(); ++i)
    for (size_t k = 0; k < model.nodes[i].children.size(); ++k) {
      const int child = model.nodes[i].children[k];
      const std::string element = node_name(int(i)) + ".children[" + std::to_string(k) + "]";
      if (child < 0 || size_t(child) >= model.nodes.size())
        gltf_fail(element, std::to_string(child) + " is out of range (the file has " + std::to_string(model.nodes.size()) +
                               " nodes)");
      if (parent[size_t(child)] >= 0)
        gltf_fail(element, node_name(child) + " has two parents, " + node_name(parent[size_t(child)]) + " and " +
                               node_name(int(i)));
      parent[size_t(child)] = int(i);
    }
  return parent;
}

// With one parent at most per node, a node is its own ancestor exactly when it cannot be reached
// from a node without a parent: such nodes are found, and one on the loop is named.
void reject_cycles(const tinygltf::Model& model, const std::vector<int>& parent) {
  std::vector<char> reached(parent.size(), 0);
  std::vector<int> stack;
  for (size_t i = 0; i < parent.size(); ++i)
    if (parent[i] < 0) stack.push_back(int(i));
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    reached[size_t(n)] = 1;
    for (int child : model.nodes[size_t(n)].children) stack.push_back(child);
  }
  for (size_t i = 0; i < parent.size(); ++i) {
    if (reached[i]) continue;
    int n = int(i);  // walk up: after parent.size() steps it is on the loop
    for (size_t step = 0; step < parent.size(); ++step) n = parent[size_t(n)];
    gltf_fail(node_name(n), "the node is its own ancestor (a cycle in the node hierarchy)");
  }
}

}  // namespace

std::vector<NodeInstance> scene_nodes(const tinygltf::Model& model, int scene, const Affine& root) {
  const std::vector<int> parent = parents(model);
  reject_cycles(model, parent);
  const tinygltf::Scene& s = model.scenes[size_t(scene)];
  std::vector<char> listed(model.nodes.size(), 0);
  std::vector<NodeInstance> stack;
  for (size_t k = s.nodes.size(); k-- > 0;) {
    const int n = s.nodes[k];
    const std::string element = "scenes[" + std::to_string(scene) + "].nodes[" + std::to_string(k) + "]";
    if (n < 0 || size_t(n) >= model.nodes.size())
      gltf_fail(element, std::to_string(n) + " is out of range (the file has " + std::to_string(model.nodes.size()) + " nodes)");
    if (parent[size_t(n)] >= 0)
      gltf_fail(element, node_name(n) + " is not a root node (it is a child of " + node_name(parent[size_t(n)]) + ")");
    if (listed[size_t(n)]) gltf_fail(element, node_name(n) + " is listed twice");
    listed[size_t(n)] = 1;
    stack.push_back({n, compose(root, node_transform(model, n))});
  }
  std::vector<NodeInstance> out;
  while (!stack.empty()) {
    NodeInstance instance = stack.back();
    stack.pop_back();
    const auto& children = model.nodes[size_t(instance.node)].children;
    for (size_t k = children.size(); k-- > 0;)
      stack.push_back({children[k], compose(instance.world, node_transform(model, children[k]))});
    out.push_back(std::move(instance));
  }
  return out;
}

}  // namespace clpt
