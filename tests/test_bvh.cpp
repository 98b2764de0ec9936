// The bounding volume hierarchy and the triangle test (scene/bvh_build.cpp, kernels/bvh.cl,
// kernels/triangle.cl): the host's tree is well formed, from clpt's builder and, in a build with
// Embree, from Embree's (scene/bvh_embree.cpp); on the device, the hierarchy's closest hit
// equals testing every primitive, over meshes, spheres in the hierarchy and both mixed; rays aimed
// at the shared edges and vertices of closed meshes never escape them (watertightness); shadow
// rays' any-hit answers agree with closest-hit distances; and the same watertightness 1e6 away
// from the world origin.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "device_test_util.h"
#include "mesh_test_util.h"
#include "scene/device_scene.h"
#include "util/error.h"

namespace clpt::test {
namespace {

Scene scene_with(std::vector<TriangleMesh> meshes, std::vector<Sphere> spheres = {}) {
  Scene scene;
  scene.file = "test";
  scene.camera.position = {0.25, -0.5, 7};
  scene.camera.look_at = {0, 0, 0};
  scene.meshes = std::move(meshes);
  scene.spheres = std::move(spheres);
  return scene;
}

std::vector<Sphere> random_spheres(std::mt19937& rng, int count, double extent) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Sphere> spheres;
  for (int i = 0; i < count; ++i) {
    Sphere s;
    s.name = "ball" + std::to_string(i);
    s.center = {extent * u(rng), extent * u(rng), extent * u(rng)};
    s.radius = 0.05 + 0.2 * (u(rng) + 1);
    s.material = lambertian(0.5);
    spheres.push_back(s);
  }
  return spheres;
}

Vec3 unit_of(const Vec3& v) {
  const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  return {v[0] / l, v[1] / l, v[2] / l};
}

struct Ray {
  Vec3 origin;  // world
  Vec3 direction;
};

struct DeviceAnswer {
  float t;
  int sphere, triangle;
  bool blocked_before, blocked_after;
};

// Runs probe_scene_hit (tests/kernels/probe_stages.cl) on world-space rays; shadow distances at
// (1 -+ 1e-4) of `shadow_at` per ray -+ 1e-5 (the boxes' slab test rounds like coordinates of
// size 3, about 1e-6 absolute, which a relative margin alone misses for hits very near the origin).
std::vector<DeviceAnswer> query_with(const std::string& options, const Scene& scene, const DeviceScene& ds,
                                     const std::vector<Ray>& rays, bool brute_force, const std::vector<float>& shadow_at) {
  std::vector<cl_float4> packed;
  std::vector<cl_float2> shadow;
  for (size_t i = 0; i < rays.size(); ++i) {
    const Ray& r = rays[i];
    const Vec3& c = scene.camera.position;
    packed.push_back({{float(r.origin[0] - c[0]), float(r.origin[1] - c[1]), float(r.origin[2] - c[2]), 0}});
    packed.push_back({{float(r.direction[0]), float(r.direction[1]), float(r.direction[2]), 0}});
    const float at = shadow_at.empty() ? 1.0f : shadow_at[i];
    shadow.push_back({{at * (1 - 1e-4f) - 1e-5f, at * (1 + 1e-4f) + 1e-5f}});
  }
  GpuRenderParams params{};
  params.sphere_count = ds.loop_spheres;
  params.bvh_node_count = cl_uint(ds.bvh.nodes.size());
  params.ray_epsilon = ds.ray_epsilon;
  Kernel kernel(test_program("probe_stages.cl", options), "probe_scene_hit", test_device().where());
  Buffer spheres = upload(ds.spheres), nodes = upload(hierarchy_device_data(ds)), triangles = upload(ds.triangles);
  Buffer in = upload(packed), shadow_in = upload(shadow);
  Buffer out(test_device(), rays.size() * 2 * sizeof(cl_float4), CL_MEM_WRITE_ONLY, "answers");
  kernel.set_arg(0, spheres);
  kernel.set_arg(1, nodes);
  kernel.set_arg(2, triangles);
  kernel.set_arg(3, params);
  kernel.set_arg(4, cl_uint(brute_force ? 1 : 0));
  kernel.set_arg(5, cl_uint(ds.spheres.size()));
  kernel.set_arg(6, cl_uint(ds.triangles.size()));
  kernel.set_arg(7, in);
  kernel.set_arg(8, shadow_in);
  kernel.set_arg(9, out);
  test_device().launch(kernel, rays.size(), 0, "probe_scene_hit");
  const std::vector<cl_float4> raw = download<cl_float4>(out, rays.size() * 2);
  std::vector<DeviceAnswer> answers;
  for (size_t i = 0; i < rays.size(); ++i) {
    const cl_float4& a = raw[2 * i];
    const cl_float4& b = raw[2 * i + 1];
    answers.push_back({a.s[0], int(a.s[1]), int(a.s[2]), b.s[0] != 0, b.s[1] != 0});
  }
  return answers;
}

// The answers of the hierarchy (or the brute force), with a leaf's four triangles in one vector
// test (CPUs); the same query with them tested one at a time (GPUs: CLPT_WIDE_LEAF_TEST=0,
// kernels/bvh.cl) must give the same answers bit for bit.
std::vector<DeviceAnswer> query(const Scene& scene, const DeviceScene& ds, const std::vector<Ray>& rays,
                                bool brute_force, const std::vector<float>& shadow_at = {}) {
  const std::vector<DeviceAnswer> wide = query_with("-cl-std=CL1.2", scene, ds, rays, brute_force, shadow_at);
  if (brute_force) return wide;
  const std::vector<DeviceAnswer> one = query_with("-cl-std=CL1.2 -DCLPT_WIDE_LEAF_TEST=0", scene, ds, rays, false, shadow_at);
  for (size_t i = 0; i < rays.size(); ++i) {
    EXPECT_EQ(std::memcmp(&wide[i].t, &one[i].t, sizeof(float)), 0) << "ray " << i << ": " << wide[i].t << " vs " << one[i].t;
    EXPECT_EQ(wide[i].sphere, one[i].sphere) << "ray " << i;
    EXPECT_EQ(wide[i].triangle, one[i].triangle) << "ray " << i;
    EXPECT_EQ(wide[i].blocked_before, one[i].blocked_before) << "ray " << i;
    EXPECT_EQ(wide[i].blocked_after, one[i].blocked_after) << "ray " << i;
  }
  return wide;
}

std::vector<Ray> random_rays(std::mt19937& rng, int count, double extent) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::normal_distribution<double> g;
  std::vector<Ray> rays;
  for (int i = 0; i < count; ++i)
    rays.push_back({{extent * u(rng), extent * u(rng), extent * u(rng)}, unit_of({g(rng), g(rng), g(rng)})});
  return rays;
}

// Scenes for the brute-force comparison: a soup, closed meshes, many spheres (in the hierarchy),
// and spheres and triangles mixed.
std::vector<Scene> comparison_scenes() {
  std::mt19937 rng(7);
  std::vector<Scene> scenes;
  scenes.push_back(scene_with({random_soup(rng, 3000, {0, 0, 0}, 2.0, 0.3, lambertian(0.5))}));
  scenes.push_back(scene_with({tessellated_sphere({0.3, 0.1, -0.2}, 1.3, 40, 60, lambertian(0.5)),
                               closed_box({-2.5, -2.5, -2.5}, {2.5, 2.5, 2.5}, lambertian(0.5))}));
  scenes.push_back(scene_with({}, random_spheres(rng, 200, 2.0)));
  // Large spheres among small ones: the large stay in the loop (loop_spheres), the rest in the tree.
  std::vector<Sphere> walls = random_spheres(rng, 60, 2.0);
  for (int k = 0; k < 3; ++k) {
    walls[size_t(k)].radius = 1e4;
    walls[size_t(k)].center = {k == 0 ? -1e4 - 3 : 0.0, k == 1 ? -1e4 - 3 : 0.0, k == 2 ? -1e4 - 3 : 0.0};
  }
  scenes.push_back(scene_with({random_soup(rng, 500, {0, 0, 0}, 2.0, 0.4, lambertian(0.5))}, walls));
  scenes.push_back(scene_with({random_soup(rng, 1500, {0, 0, 0}, 2.0, 0.4, lambertian(0.5)),
                               tessellated_sphere({-1, 0.5, 0.5}, 0.7, 12, 20, lambertian(0.5))},
                              random_spheres(rng, 100, 2.0)));
  return scenes;
}

// clpt's builder, and Embree's when this build has it.
std::vector<BvhBuilder> builders_here() {
  if (!embree_available()) return {BvhBuilder::Clpt};
  return {BvhBuilder::Clpt, BvhBuilder::Embree, BvhBuilder::EmbreeOneThread};
}

// The collapsed 4-wide tree (scene/bvh_build.cpp, collapse_bvh): every node but the root is the
// child of exactly one slot, after its parent; occupied slots first, empty ones inverted and
// zero; a node of fewer than 4 children has only leaves (the collapse opens interior children
// until 4); every child box contains its subtree (an interior child's box holds all its node's
// child boxes, a leaf's box its triangles' vertices and its spheres' centres); every primitive
// is in exactly one leaf; the stack the tree can need is recomputed and within CLPT_BVH_STACK.
// Some of the scenes have meshes of large triangles beside others (a floor, a mirror box): there
// the root holds the two subtrees of graft_loop_tree.
TEST(BvhBuild, EveryPrimitiveInOneLeafAndBoxesNest) {
  for (BvhBuilder builder : builders_here())
  for (const Scene& scene : comparison_scenes()) {
    SCOPED_TRACE(bvh_builder_name(builder));
    const DeviceScene ds = make_device_scene(scene, 4, 3, Precision::Robust, builder);
    const Bvh& bvh = ds.bvh;
    ASSERT_FALSE(bvh.nodes.empty());
    EXPECT_TRUE(bvh.binary.empty());
    EXPECT_LE(bvh.stack_need, CLPT_BVH_STACK);
    EXPECT_GE(bvh.binary_depth, bvh.depth);
    // At most (2n + 2) / 3 nodes for n primitives (render/limits.h, kMaxBvhNodes).
    EXPECT_LE(3 * bvh.nodes.size(), 2 * (bvh.triangle_order.size() + bvh.sphere_order.size()) + 2);
    std::vector<int> tri_seen(ds.triangles.size(), 0), sphere_seen(ds.spheres.size(), 0);
    std::vector<int> parents(bvh.nodes.size(), 0);
    std::vector<int> need(bvh.nodes.size(), 0);
    // Backwards: children come after their parents, so each child's need is known first.
    for (size_t i = bvh.nodes.size(); i-- > 0;) {
      const GpuBvhNode& n = bvh.nodes[i];
      const float* lower[3] = {n.lower_x, n.lower_y, n.lower_z};
      const float* upper[3] = {n.upper_x, n.upper_y, n.upper_z};
      int used = 0, interior = 0, deepest = 0;
      for (int s = 0; s < CLPT_BVH_WIDTH; ++s) {
        if (!(n.lower_x[s] <= n.upper_x[s])) {
          // Empty: inverted on every axis, after the occupied slots, and naming nothing.
          for (int k = 0; k < 3; ++k) EXPECT_GT(lower[k][s], upper[k][s]);
          EXPECT_EQ(n.child[s], 0u);
          EXPECT_EQ(n.count[s], 0u);
          continue;
        }
        EXPECT_EQ(used, s) << "node " << i << ": an occupied slot after an empty one";
        ++used;
        if (n.count[s] == 0) {
          ++interior;
          ASSERT_LT(n.child[s], bvh.nodes.size());
          ASSERT_GT(n.child[s], i);
          ++parents[n.child[s]];
          deepest = std::max(deepest, need[n.child[s]]);
          const GpuBvhNode& c = bvh.nodes[n.child[s]];
          const float* c_lower[3] = {c.lower_x, c.lower_y, c.lower_z};
          const float* c_upper[3] = {c.upper_x, c.upper_y, c.upper_z};
          for (int t = 0; t < CLPT_BVH_WIDTH; ++t) {
            if (!(c.lower_x[t] <= c.upper_x[t])) continue;
            for (int k = 0; k < 3; ++k) {
              EXPECT_LE(lower[k][s], c_lower[k][t]);
              EXPECT_GE(upper[k][s], c_upper[k][t]);
            }
          }
          continue;
        }
        const bool spheres = n.count[s] & CLPT_BVH_SPHERE_LEAF;
        std::vector<int>& seen = spheres ? sphere_seen : tri_seen;
        const uint32_t count = n.count[s] & CLPT_BVH_COUNT_MASK;
        EXPECT_GE(count, 1u);
        ASSERT_LE(n.child[s] + count, seen.size());
        for (uint32_t j = n.child[s]; j < n.child[s] + count; ++j) {
          ++seen[j];
          std::vector<std::array<double, 3>> points;
          if (spheres) {
            const GpuSphere& sp = ds.spheres[j];
            const double r = double(sp.radius) + sp.radius_lo;
            std::array<double, 3> centre;
            for (int k = 0; k < 3; ++k)
              centre[size_t(k)] = double(sp.surface_point[k]) + sp.surface_point_lo[k] -
                                  r * (double(sp.surface_normal[k]) + sp.surface_normal_lo[k]);
            points.push_back(centre);
          } else {
            for (const float* v : {ds.triangles[j].v0, ds.triangles[j].v1, ds.triangles[j].v2})
              points.push_back({v[0], v[1], v[2]});
          }
          for (const auto& p : points)
            for (int k = 0; k < 3; ++k) {
              EXPECT_LE(lower[k][s], p[size_t(k)]);
              EXPECT_GE(upper[k][s], p[size_t(k)]);
            }
        }
      }
      EXPECT_GE(used, 1);
      // Not the root above a triangle loop's meshes (graft_loop_tree): its two subtrees by design.
      if (used < CLPT_BVH_WIDTH && !(i == 0 && ds.loop_triangles > 0)) {
        EXPECT_EQ(interior, 0) << "node " << i << " could have opened an interior child";
      }
      need[i] = used - 1 + deepest;
    }
    EXPECT_EQ(parents[0], 0);
    for (size_t i = 1; i < parents.size(); ++i) EXPECT_EQ(parents[i], 1) << "node " << i;
    EXPECT_EQ(need[0], bvh.stack_need);
    for (int s : tri_seen) EXPECT_EQ(s, 1);
    // The loop's spheres come first and are in no leaf; every other sphere is in exactly one.
    if (spheres_in_hierarchy(scene)) {
      for (size_t i = 0; i < sphere_seen.size(); ++i) EXPECT_EQ(sphere_seen[i], i < ds.loop_spheres ? 0 : 1) << i;
    }
  }
}

// The hierarchy's device buffer (hierarchy_device_data): the nodes, a triangle leaf's child made
// the index of its first block, sphere leaves and interior children as they were; the blocks hold
// each leaf's triangles four by four in order, unused lanes zero; its size as announced.
TEST(BvhBuild, LeafBlocksHoldEachLeafsTrianglesInOrder) {
  for (const Scene& scene : comparison_scenes()) {
    const DeviceScene ds = make_device_scene(scene, 4, 3);
    const std::vector<uint8_t> data = hierarchy_device_data(ds);
    ASSERT_EQ(data.size(), hierarchy_device_bytes(ds));
    const size_t nodes = ds.bvh.nodes.size();
    ASSERT_EQ((data.size() - nodes * sizeof(GpuBvhNode)) % sizeof(GpuTriangleBlock), 0u);
    const size_t blocks = (data.size() - nodes * sizeof(GpuBvhNode)) / sizeof(GpuTriangleBlock);
    std::vector<GpuBvhNode> device_nodes(nodes);
    std::vector<GpuTriangleBlock> block(blocks);
    if (nodes > 0) std::memcpy(device_nodes.data(), data.data(), nodes * sizeof(GpuBvhNode));
    if (blocks > 0)  // a scene of spheres alone has none (memcpy from a null pointer is undefined)
      std::memcpy(block.data(), data.data() + nodes * sizeof(GpuBvhNode), blocks * sizeof(GpuTriangleBlock));
    std::vector<int> used(blocks, 0);
    size_t triangles = 0;
    for (size_t n = 0; n < nodes; ++n)
      for (int s = 0; s < CLPT_BVH_WIDTH; ++s) {
        const uint32_t count = ds.bvh.nodes[n].count[s];
        EXPECT_EQ(device_nodes[n].count[s], count);
        if (count == 0u || (count & CLPT_BVH_SPHERE_LEAF)) {
          EXPECT_EQ(device_nodes[n].child[s], ds.bvh.nodes[n].child[s]);
          continue;
        }
        const uint32_t first = ds.bvh.nodes[n].child[s];
        for (uint32_t k = 0; k < count; ++k) {
          const size_t b = device_nodes[n].child[s] + k / 4, lane = k % 4;
          ASSERT_LT(b, blocks);
          used[b] += lane == 0 ? 1 : 0;
          EXPECT_EQ(block[b].first, first + k - lane);
          EXPECT_EQ(block[b].count, std::min<uint32_t>(4u, count - (k - uint32_t(lane))));
          const GpuTriangle& t = ds.triangles[first + k];
          const float* v[3] = {t.v0, t.v1, t.v2};
          for (int vertex = 0; vertex < 3; ++vertex)
            for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(block[b].v[vertex][axis][lane], v[vertex][axis]);
          ++triangles;
        }
      }
    EXPECT_EQ(triangles, ds.triangles.size());
    for (size_t b = 0; b < blocks; ++b) {
      EXPECT_EQ(used[b], 1) << "block " << b;
      for (uint32_t lane = block[b].count; lane < 4; ++lane)
        for (int vertex = 0; vertex < 3; ++vertex)
          for (int axis = 0; axis < 3; ++axis) EXPECT_EQ(block[b].v[vertex][axis][lane], 0.0f);
    }
  }
}

// The collapse of a hand-built binary tree: the child of the largest area is opened first.
// A hierarchy of triangles alone is built with its leaves charged by their blocks of four
// (BvhBuildOptions::leaf_group, make_device_scene): a subtree of four triangles or fewer costs one
// block test as a leaf, less than any split of it, so none is split and leaves fill their blocks.
// Where spheres are in the hierarchy (tested one at a time) every primitive costs one test.
TEST(BvhBuild, TriangleLeavesAreChargedByTheirBlocks) {
  for (const Scene& scene : comparison_scenes()) {
    const DeviceScene ds = make_device_scene(scene, 4, 3);
    if (ds.bvh.nodes.empty()) continue;
    bool spheres = false;
    // Primitives under child slot s of node n.
    std::function<uint32_t(uint32_t, int)> under = [&](uint32_t n, int s) -> uint32_t {
      const uint32_t count = ds.bvh.nodes[n].count[s];
      if (count != 0u) {
        spheres = spheres || (count & CLPT_BVH_SPHERE_LEAF) != 0u;
        return count & CLPT_BVH_COUNT_MASK;
      }
      const GpuBvhNode& node = ds.bvh.nodes[n];
      if (node.lower_x[s] > node.upper_x[s]) return 0u;  // empty slot
      uint32_t total = 0;
      for (int k = 0; k < CLPT_BVH_WIDTH; ++k) total += under(node.child[s], k);
      return total;
    };
    uint32_t smallest_interior = UINT32_MAX;
    size_t leaves = 0, triangles = 0;
    for (uint32_t n = 0; n < ds.bvh.nodes.size(); ++n)
      for (int s = 0; s < CLPT_BVH_WIDTH; ++s) {
        const GpuBvhNode& node = ds.bvh.nodes[n];
        if (node.count[s] != 0u) {
          ++leaves;
          triangles += (node.count[s] & CLPT_BVH_SPHERE_LEAF) ? 0u : (node.count[s] & CLPT_BVH_COUNT_MASK);
        } else if (node.lower_x[s] <= node.upper_x[s]) {
          smallest_interior = std::min(smallest_interior, under(n, s));
        }
      }
    if (spheres) {
      EXPECT_EQ(ds.bvh.leaf_group, 1);
      continue;
    }
    EXPECT_EQ(ds.bvh.leaf_group, int(kTriangleBlockLanes));
    EXPECT_GT(smallest_interior, kTriangleBlockLanes) << "an interior node over four triangles or fewer";
    // Fuller leaves than a per-triangle SAH gives these soups and meshes (about 2 a leaf).
    EXPECT_GT(double(triangles) / double(leaves), 2.5);
  }
}

TEST(BvhBuild, CollapseOpensTheLargestChildFirst) {
  // Binary (depth first): 0 = root(1, 2); 1 = interior(small: 3, 4)... laid out as the builders do.
  auto box = [](float lo, float hi) {
    BvhBox b;
    b.lower = {lo, 0, 0};
    b.upper = {hi, 1, 1};
    return b;
  };
  std::vector<BvhPrimitive> prims(6);
  for (uint32_t i = 0; i < 6; ++i) {
    prims[i].box = box(float(i), float(i) + 1);
    prims[i].index = i;
  }
  Bvh bvh;
  // root [0,6] -> A [0,2] (leaves p0, p1), B [2,6] -> C [2,4] (p2, p3), D [4,6] (p4, p5).
  const uint32_t root = push_bvh_node(bvh, box(0, 6));
  const uint32_t a = push_bvh_node(bvh, box(0, 2));
  make_bvh_leaf(bvh, push_bvh_node(bvh, box(0, 1)), &prims[0], &prims[1]);
  bvh.binary[a].first = uint32_t(bvh.binary.size());
  make_bvh_leaf(bvh, push_bvh_node(bvh, box(1, 2)), &prims[1], &prims[2]);
  bvh.binary[root].first = uint32_t(bvh.binary.size());
  const uint32_t b = push_bvh_node(bvh, box(2, 6));
  const uint32_t c = push_bvh_node(bvh, box(2, 4));
  make_bvh_leaf(bvh, push_bvh_node(bvh, box(2, 3)), &prims[2], &prims[3]);
  bvh.binary[c].first = uint32_t(bvh.binary.size());
  make_bvh_leaf(bvh, push_bvh_node(bvh, box(3, 4)), &prims[3], &prims[4]);
  bvh.binary[b].first = uint32_t(bvh.binary.size());
  make_bvh_leaf(bvh, push_bvh_node(bvh, box(4, 6)), prims.data() + 4, prims.data() + 6);
  collapse_bvh(bvh);
  // The root opens B (area of [2,6] beats A's [0,2]), then A: slots A's p0, A's p1, C, D.
  ASSERT_EQ(bvh.nodes.size(), 2u);
  const GpuBvhNode& r = bvh.nodes[0];
  EXPECT_EQ(r.count[0], 1u);
  EXPECT_EQ(r.child[0], 0u);
  EXPECT_EQ(r.count[1], 1u);
  EXPECT_EQ(r.child[1], 1u);
  EXPECT_EQ(r.count[2], 0u);  // C, interior: node 1
  EXPECT_EQ(r.child[2], 1u);
  EXPECT_EQ(r.lower_x[2], 2.0f);
  EXPECT_EQ(r.upper_x[2], 4.0f);
  EXPECT_EQ(r.count[3], 2u);  // D, a leaf of p4 and p5
  EXPECT_EQ(r.child[3], 4u);
  EXPECT_EQ(bvh.nodes[1].count[0], 1u);
  EXPECT_EQ(bvh.nodes[1].count[1], 1u);
  EXPECT_GT(bvh.nodes[1].lower_x[2], bvh.nodes[1].upper_x[2]);  // empty
  EXPECT_EQ(bvh.depth, 2);
  EXPECT_EQ(bvh.stack_need, 3 + 1);
  EXPECT_TRUE(bvh.binary.empty());
}

// A binary tree whose collapse needs 3 stack entries for every 2 binary levels (each node X has two
// interior children A and B, A over two leaves and B over a leaf and the next X): 22 such levels
// (44 binary levels, within the builders' CLPT_BVH_STACK) could need 3 * 22 entries, more than
// the kernels' stack; the collapse refuses it, naming the stack.
TEST(BvhBuild, CollapseRefusesATreeItsStackCannotHold) {
  const int levels = 22;
  std::vector<BvhPrimitive> prims(size_t(4 * levels + 1));
  for (size_t i = 0; i < prims.size(); ++i) {
    prims[i].box.lower = {float(i), 0, 0};
    prims[i].box.upper = {float(i) + 1, 1, 1};
    prims[i].index = uint32_t(i);
  }
  BvhBox all;
  all.lower = {0, 0, 0};
  all.upper = {float(prims.size()), 1, 1};
  Bvh bvh;
  size_t next = 0;
  auto leaf = [&] { make_bvh_leaf(bvh, push_bvh_node(bvh, all), &prims[next], &prims[next] + 1), ++next; };
  for (int level = 0; level < levels; ++level) {
    const uint32_t x = push_bvh_node(bvh, all);
    const uint32_t a = push_bvh_node(bvh, all);
    leaf();
    bvh.binary[a].first = uint32_t(bvh.binary.size());
    leaf();
    bvh.binary[x].first = uint32_t(bvh.binary.size());
    const uint32_t b = push_bvh_node(bvh, all);
    leaf();
    bvh.binary[b].first = uint32_t(bvh.binary.size());
  }
  leaf();  // the last B's second child
  const auto [code, message] = [&] {
    try {
      collapse_bvh(bvh);
    } catch (const Error& e) {
      return std::make_pair(e.code(), std::string(e.what()));
    }
    return std::make_pair(ExitCode::Ok, std::string());
  }();
  EXPECT_EQ(code, ExitCode::BadScene);
  EXPECT_NE(message.find("traversal stack"), std::string::npos) << message;
  EXPECT_NE(message.find(std::to_string(CLPT_BVH_STACK)), std::string::npos) << message;
}

TEST(BvhTraversal, ClosestHitEqualsBruteForceOverEveryPrimitive) {
  std::mt19937 rng(11);
  int rays_total = 0, misses = 0, ties = 0;
  for (BvhBuilder builder : builders_here())
  for (const Scene& scene : comparison_scenes()) {
    SCOPED_TRACE(bvh_builder_name(builder));
    const DeviceScene ds = make_device_scene(scene, 4, 3, Precision::Robust, builder);
    const std::vector<Ray> rays = random_rays(rng, 30000, 3.0);
    const auto bvh = query(scene, ds, rays, false);
    const auto brute = query(scene, ds, rays, true);
    for (size_t i = 0; i < rays.size(); ++i) {
      ASSERT_EQ(bvh[i].t, brute[i].t) << scene.meshes.size() << " meshes, ray " << i;
      const bool same = bvh[i].sphere == brute[i].sphere && bvh[i].triangle == brute[i].triangle;
      ties += same ? 0 : 1;  // equal distances to two primitives (a shared edge): either may report
      misses += bvh[i].t >= 1e29f ? 1 : 0;
    }
    rays_total += int(rays.size());
  }
  EXPECT_GE(rays_total, 100000);
  EXPECT_LT(ties, rays_total / 1000);
  EXPECT_GT(rays_total - misses, rays_total / 5);  // enough rays hit something for the comparison to mean something
}

// Ray origins inside a closed mesh, aimed exactly at its vertices and at points on its edges
// (midpoints and random points), must hit the mesh: no ray slips between two triangles.
TEST(BvhTraversal, RaysAtSharedEdgesAndVerticesOfClosedMeshesNeverEscape) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  const std::vector<Scene> scenes = {
      scene_with({tessellated_sphere({0.1, -0.2, 0.3}, 1.7, 64, 96, lambertian(0.5))}),
      scene_with({closed_box({-1.1, -0.9, -1.3}, {1.2, 1.0, 0.8}, lambertian(0.5))}),
      scene_with({tessellated_sphere({0, 0, 0}, 2.5e3, 30, 45, lambertian(0.5))})};
  int total = 0;
  for (const Scene& scene : scenes) {
    const TriangleMesh& mesh = scene.meshes[0];
    // The centre of the mesh's bounding box and its smallest half extent: both meshes are convex
    // and hold the box of half that size around the centre.
    Vec3 lo = mesh.positions[0], hi = mesh.positions[0];
    for (const Vec3& p : mesh.positions)
      for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
    const Vec3 centre = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    const double r = std::min({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) / 2;
    const DeviceScene ds = make_device_scene(scene, 4, 3);
    std::vector<Ray> rays;
    const int per_scene = scene.meshes[0].triangles.size() > 100 ? 450000 : 100000;
    while (int(rays.size()) < per_scene) {
      const auto& tri = mesh.triangles[rng() % mesh.triangles.size()];
      const int e = int(rng() % 3);
      const Vec3& a = mesh.positions[tri[e]];
      const Vec3& b = mesh.positions[tri[(e + 1) % 3]];
      const int pick = int(rng() % 3);  // a vertex, an edge midpoint, a random point on the edge
      const double s = pick == 0 ? 0.0 : pick == 1 ? 0.5 : u(rng);
      const Vec3 target = {a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
      // Origins inside: within 0.3 of the size around the centre (the box and spheres contain it).
      const Vec3 o = {centre[0] + 0.3 * r * v(rng), centre[1] + 0.3 * r * v(rng), centre[2] + 0.3 * r * v(rng)};
      rays.push_back({o, unit_of({target[0] - o[0], target[1] - o[1], target[2] - o[2]})});
    }
    const auto answers = query(scene, ds, rays, false);
    int escaped = 0;
    for (const DeviceAnswer& a : answers) escaped += a.triangle < 0 ? 1 : 0;
    EXPECT_EQ(escaped, 0) << mesh.triangles.size() << " triangles";
    total += int(rays.size());
  }
  EXPECT_GE(total, 1000000);
}

// Any-hit shadow queries agree with the closest hit: nothing blocks a ray before (1 - 1e-4) of its
// closest hit (less 1e-5), something blocks it before (1 + 1e-4) of it (plus 1e-5).
TEST(BvhTraversal, ShadowAnyHitAgreesWithClosestHitDistance) {
  std::mt19937 rng(17);
  for (const Scene& scene : comparison_scenes()) {
    const DeviceScene ds = make_device_scene(scene, 4, 3);
    const std::vector<Ray> rays = random_rays(rng, 20000, 3.0);
    const auto closest = query(scene, ds, rays, false);
    std::vector<float> at;  // a ray whose closest hit is a loop sphere asks up to that distance too
    for (const DeviceAnswer& a : closest) at.push_back(a.t < 1e29f ? a.t : 1e6f);
    const auto shadow = query(scene, ds, rays, false, at);
    int hits = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
      // The any-hit query covers the hierarchy; the loop's spheres are the caller's (path.cl).
      const bool in_loop = closest[i].sphere >= 0 && closest[i].sphere < int(ds.loop_spheres);
      const bool hit = closest[i].t < 1e29f && !in_loop;
      hits += hit ? 1 : 0;
      ASSERT_FALSE(shadow[i].blocked_before) << "ray " << i << " at t " << closest[i].t;
      ASSERT_EQ(shadow[i].blocked_after, hit) << "ray " << i << " at t " << closest[i].t;
    }
    EXPECT_GT(hits, 1000);
  }
}

// The same far from the world origin (issue 35): closed meshes 1e6 away from it, with the camera
// beside them (small camera-relative coordinates, the usual case) and with the camera at the
// origin (camera-relative coordinates of 1e6, whose floats are 1/16 apart). Rays start inside and
// aim at points of the shared edges and at the vertices of the triangles as the device stores them
// (camera-relative floats), so adjacent triangles share those points exactly; none may escape.
TEST(BvhTraversal, RaysAtSharedEdgesAndVerticesFarFromTheOriginNeverEscape) {
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  const Vec3 far = {1e6, -1e6, 1e6};
  struct Case {
    TriangleMesh mesh;
    Vec3 camera;
  };
  const std::vector<Case> cases = {
      {tessellated_sphere({far[0] + 0.1, far[1] - 0.2, far[2] + 0.3}, 1.7, 64, 96, lambertian(0.5)),
       {far[0] + 0.25, far[1] - 0.5, far[2] + 7}},
      {closed_box({far[0] - 1.1, far[1] - 0.9, far[2] - 1.3}, {far[0] + 1.2, far[1] + 1.0, far[2] + 0.8}, lambertian(0.5)),
       {far[0] + 0.25, far[1] - 0.5, far[2] + 7}},
      {tessellated_sphere(far, 300, 30, 45, lambertian(0.5)), {0, 0, 0}},
      {closed_box({far[0] - 200, far[1] - 150, far[2] - 250}, {far[0] + 220, far[1] + 170, far[2] + 180}, lambertian(0.5)),
       {0, 0, 0}}};
  int total = 0;
  for (const Case& c : cases) {
    Scene scene;
    scene.file = "far";
    scene.camera.position = c.camera;
    scene.camera.look_at = far;
    scene.meshes = {c.mesh};
    const DeviceScene ds = make_device_scene(scene, 4, 3);
    // The stored triangles' box, camera-relative: the meshes are convex and hold the box of 0.3 of
    // its smallest half extent around its centre.
    Vec3 lo = {1e30, 1e30, 1e30}, hi = {-1e30, -1e30, -1e30};
    for (const GpuTriangle& t : ds.triangles)
      for (const float* p : {t.v0, t.v1, t.v2})
        for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], double(p[k])), hi[k] = std::max(hi[k], double(p[k]));
    const Vec3 centre = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    const double r = std::min({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]}) / 2;
    std::vector<Ray> rays;
    const int per_case = ds.triangles.size() > 100 ? 200000 : 60000;
    while (int(rays.size()) < per_case) {
      const GpuTriangle& t = ds.triangles[rng() % ds.triangles.size()];
      const float* corner[3] = {t.v0, t.v1, t.v2};
      const int e = int(rng() % 3);
      const float* a = corner[e];
      const float* b = corner[(e + 1) % 3];
      const int pick = int(rng() % 3);  // a vertex, an edge midpoint, a random point on the edge
      const double f = pick == 0 ? 0.0 : pick == 1 ? 0.5 : u(rng);
      const Vec3 target = {a[0] + f * (double(b[0]) - a[0]), a[1] + f * (double(b[1]) - a[1]), a[2] + f * (double(b[2]) - a[2])};
      // A camera-relative origin exact in float, so that query() passes it on unchanged.
      const Vec3 o = {double(float(centre[0] + 0.3 * r * v(rng))), double(float(centre[1] + 0.3 * r * v(rng))),
                      double(float(centre[2] + 0.3 * r * v(rng)))};
      rays.push_back({{c.camera[0] + o[0], c.camera[1] + o[1], c.camera[2] + o[2]},
                      unit_of({target[0] - o[0], target[1] - o[1], target[2] - o[2]})});
    }
    const auto answers = query(scene, ds, rays, false);
    int escaped = 0;
    for (const DeviceAnswer& a : answers) escaped += a.triangle < 0 ? 1 : 0;
    EXPECT_EQ(escaped, 0) << c.mesh.triangles.size() << " triangles, camera at " << c.camera[0];
    total += int(rays.size());
  }
  EXPECT_GE(total, 500000);
}

}  // namespace
}  // namespace clpt::test
