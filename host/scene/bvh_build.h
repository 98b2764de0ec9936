// The bounding volume hierarchy the kernels traverse (kernels/bvh.cl): built on the host by a
// binned surface area heuristic over primitive boxes into a binary tree (BvhBinaryNode, depth
// first), then collapsed into the kernels' 4-wide nodes (GpuBvhNode, kernels/types.h) by
// collapse_bvh. Leaves hold primitives of one kind, so the kernels' leaf loops test only
// triangles or only spheres.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "kernels/types.h"

namespace clpt {

enum class PrimitiveKind : uint32_t { Triangle = 0, Sphere = 1 };

// An axis-aligned box in the kernels' (camera-relative, float) coordinates.
struct BvhBox {
  std::array<float, 3> lower{{1e30f, 1e30f, 1e30f}};
  std::array<float, 3> upper{{-1e30f, -1e30f, -1e30f}};
  void grow(const BvhBox& b);
  void grow(const std::array<float, 3>& p);
  double half_area() const;  // 0 for an empty box
};

struct BvhPrimitive {
  BvhBox box;
  PrimitiveKind kind = PrimitiveKind::Triangle;
  uint32_t index = 0;  // the primitive's index among those of its kind, in the caller's order
};

struct BvhBuildOptions {
  int bins = 16;      // candidate split planes per axis and node
  int max_leaf = 4;   // a range this small (or smaller) may become a leaf when the SAH says so
  double traversal_cost = 1.0;  // SAH cost of visiting a node, against 1 per primitive test
  // Primitives a leaf tests together: the SAH counts a leaf (and each side of a split) as
  // ceil(n / leaf_group) tests. make_device_scene sets 4 for a hierarchy of triangles alone, whose
  // leaves the kernels read as blocks of four (GpuTriangleBlock); 1 where spheres are in it.
  int leaf_group = 1;
  // Threads of the build (std::thread); 0: one per hardware thread. The hierarchy is the same for
  // any count (the nodes and leaf orders, byte for byte), only its build time differs.
  int threads = 0;
};

// A node of the binary tree the builders write (the layout the kernels traversed before the 4-wide
// nodes): an interior node's first child is the next node, its second node `first`; a leaf holds
// `count & CLPT_BVH_COUNT_MASK` primitives from `first` (| CLPT_BVH_SPHERE_LEAF: spheres).
struct BvhBinaryNode {
  float lower[3];
  uint32_t first;  // interior: index of the second child; leaf: first primitive
  float upper[3];
  uint32_t count;  // interior: 0; leaf: primitive count, | CLPT_BVH_SPHERE_LEAF for spheres
};

struct Bvh {
  // The kernels' 4-wide nodes (collapse_bvh): nodes[0] is the root, every node after its parent;
  // empty for no primitives.
  std::vector<GpuBvhNode> nodes;
  // The builders' binary tree, depth first; emptied by collapse_bvh once `nodes` holds it.
  std::vector<BvhBinaryNode> binary;
  // Leaf order: triangle_order[i] is the caller's index of the triangle the kernels store at i
  // (a leaf's GpuBvhNode.child counts in this order); likewise sphere_order. The collapse keeps it.
  std::vector<uint32_t> triangle_order;
  std::vector<uint32_t> sphere_order;
  int binary_depth = 0;    // binary nodes on the longest root-to-leaf path (the builders' recursion)
  int depth = 0;           // 4-wide nodes on the longest root-to-leaf path (collapse_bvh)
  int stack_need = 0;      // the most traversal stack entries any ray can need (collapse_bvh)
  double build_seconds = 0;
  // CPU seconds of this process during the build (all its threads): on a machine whose cores other
  // work shares, the figure that holds; 0 where not measured (Embree's builder).
  double build_cpu_seconds = 0;
  int build_threads = 1;   // threads the build could use (bvh_build_threads)
  int leaf_group = 1;      // the build's BvhBuildOptions::leaf_group, which bvh_sah_cost charges alike
};

// The threads a build with `options` uses at most: options.threads, or the hardware's.
int bvh_build_threads(const BvhBuildOptions& options);

// Builds the hierarchy over `primitives` (options.bins 2 to 32), collapsed (collapse_bvh). Throws
// Error (exit code as for scenes) when the binary tree would be deeper than CLPT_BVH_STACK levels or
// the 4-wide one could need more than the kernels' traversal stack (CLPT_BVH_STACK entries), which a
// binned SAH build of any real scene stays far below.
Bvh build_bvh(const std::vector<BvhPrimitive>& primitives, const BvhBuildOptions& options = {});

// Collapses bvh.binary into bvh.nodes, the kernels' 4-wide layout, the last step of every builder:
// at each node, the child with the largest surface area that is not a leaf is replaced by its two
// children until there are 4 or only leaves; slots keep the binary tree's left-to-right order,
// leaves and the primitive orders stay as they are. Sets depth and stack_need (the deepest stack
// the kernels' traversal can reach: at a node of c children, c - 1 pushed while one is visited)
// and throws Error(ExitCode::BadScene) when stack_need exceeds CLPT_BVH_STACK. Empties bvh.binary.
void collapse_bvh(Bvh& bvh);

// The steps every builder (this one, bvh_embree.h) writes the binary tree with, depth first:
// push_bvh_node appends a node of box `box` and returns its index (an interior node's first child
// must be pushed next, its `first` set to the second child's index and `count` to 0);
// make_bvh_leaf makes `node` a leaf of [begin, end), which must be non-empty and of one kind,
// appending their indices to the kind's order; note_bvh_depth records a node at `depth` (root 1)
// and throws Error(ExitCode::BadScene) past CLPT_BVH_STACK (bounding the builders' recursion).
uint32_t push_bvh_node(Bvh& bvh, const BvhBox& box);
void make_bvh_leaf(Bvh& bvh, uint32_t node, const BvhPrimitive* begin, const BvhPrimitive* end);
void note_bvh_depth(Bvh& bvh, int depth);

// The box of a sphere centred at `center` (camera-relative, double) with radius r, rounded
// outwards to float so that it contains the sphere the kernels intersect.
BvhBox sphere_box(const std::array<double, 3>& center, double radius);

}  // namespace clpt
