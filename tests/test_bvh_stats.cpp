// The hierarchy's statistics and build (scene/bvh_stats.cpp, scene/bvh_build.cpp) and the
// execution-form rule (render/form_rule.cpp): the SAH cost of a hand-built tree equals its closed
// form (4-wide nodes); the traversal replica counts the nodes, boxes and triangles of
// kernels/bvh.cl's order on a tiny known tree; the ray sample is deterministic; the parallel build writes the same hierarchy
// for any thread count; the form rule picks by the scene's geometry and --form overrides it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "mesh_test_util.h"
#include "render/form_rule.h"
#include "render/megakernel_renderer.h"
#include "render/render_plan.h"
#include "scene/bvh_stats.h"
#include "scene/scene_loader.h"
#include "tools/traversal_trace.h"
#include "device_test_util.h"

namespace clpt::test {
namespace {

// A 4-wide node over `slots` (box, child, count each); the rest empty (inverted boxes).
struct Slot {
  std::array<float, 3> lower, upper;
  uint32_t child, count;
};
GpuBvhNode node(std::initializer_list<Slot> slots) {
  GpuBvhNode n{};
  for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
    n.lower_x[i] = n.lower_y[i] = n.lower_z[i] = INFINITY;
    n.upper_x[i] = n.upper_y[i] = n.upper_z[i] = -INFINITY;
  }
  int i = 0;
  for (const Slot& s : slots) {
    n.lower_x[i] = s.lower[0], n.lower_y[i] = s.lower[1], n.lower_z[i] = s.lower[2];
    n.upper_x[i] = s.upper[0], n.upper_y[i] = s.upper[1], n.upper_z[i] = s.upper[2];
    n.child[i] = s.child;
    n.count[i] = s.count;
    ++i;
  }
  return n;
}

TEST(BvhStats, SahCostOfAHandBuiltTreeIsTheClosedForm) {
  // A root of box [0,2]x[0,1]x[0,1] (half area 2 + 1 + 2 = 5, its children's union) over a leaf of 2
  // primitives in [0,1]^3 (half area 3) and a leaf of 1 in [1,2]x[0,1]^2 (3): 1 * 5/5 + 2 * 3/5 +
  // 1 * 3/5 = 2.8 with a node cost of 1; 2 * 5/5 + 9/5 = 3.8 with 2.
  Bvh bvh;
  bvh.nodes = {node({{{0, 0, 0}, {1, 1, 1}, 0, 2}, {{1, 0, 0}, {2, 1, 1}, 2, 1}})};
  EXPECT_DOUBLE_EQ(bvh_sah_cost(bvh), 2.8);
  EXPECT_DOUBLE_EQ(bvh_sah_cost(bvh, 2.0), 3.8);
  // The same leaves one level down, under a root whose other child is a leaf of 1 in [0,2]x[0,1]x[1,2]:
  // root box [0,2]x[0,1]x[0,2] (half area 2 + 2 + 4 = 8): (8 + 5 + 2 * 3 + 1 * 3 + 1 * 5) / 8 = 27/8.
  Bvh two;
  two.nodes = {node({{{0, 0, 0}, {2, 1, 1}, 1, 0}, {{0, 0, 1}, {2, 1, 2}, 3, 1}}),
               node({{{0, 0, 0}, {1, 1, 1}, 0, 2}, {{1, 0, 0}, {2, 1, 1}, 2, 1}})};
  EXPECT_DOUBLE_EQ(bvh_sah_cost(two), 27.0 / 8.0);
  // A tree that is one leaf: a root holding it, one node test and its count. No nodes: 0.
  Bvh leaf;
  leaf.nodes = {node({{{0, 0, 0}, {1, 2, 3}, 0, 4}})};
  EXPECT_DOUBLE_EQ(bvh_sah_cost(leaf), 5.0);
  EXPECT_EQ(bvh_sah_cost(Bvh()), 0.0);
  // Leaves charged in groups of four (a triangle hierarchy's blocks): the first tree's leaves of 2
  // and 1 are one test each, 1 + 3/5 + 3/5 = 2.2; the single leaf of 4 one test, 1 + 1 = 2.
  bvh.leaf_group = 4;
  EXPECT_DOUBLE_EQ(bvh_sah_cost(bvh), 2.2);
  leaf.leaf_group = 4;
  EXPECT_DOUBLE_EQ(bvh_sah_cost(leaf), 2.0);
  leaf.nodes[0].count[0] = 5;  // two blocks
  EXPECT_DOUBLE_EQ(bvh_sah_cost(leaf), 3.0);
}

TEST(BvhStats, SahCostOfTheBuildersTreeIsItsRecursiveCost) {
  // The closed form against the recursion cost(n) = C_t + (A_l cost(l) + A_r cost(r)) / A_n.
  std::mt19937 rng(3);
  Scene scene;
  scene.camera.position = {0, 0, 8};
  scene.meshes = {random_soup(rng, 2000, {0, 0, 0}, 2.0, 0.3, lambertian(0.5))};
  const DeviceScene ds = make_device_scene(scene, 4, 3);
  ASSERT_EQ(ds.bvh.leaf_group, 4);  // triangles alone: leaves are charged by their blocks of four
  const std::vector<GpuBvhNode>& n = ds.bvh.nodes;
  auto area = [](const GpuBvhNode& b, int i) {
    const double x = double(b.upper_x[i]) - b.lower_x[i], y = double(b.upper_y[i]) - b.lower_y[i],
                 z = double(b.upper_z[i]) - b.lower_z[i];
    return x < 0 ? 0.0 : x * y + y * z + z * x;
  };
  // cost(node of box area A) = C_t + sum over its children of A_child cost(child) / A, a leaf's
  // cost its blocks (ceil(count / 4)); the root's box is the union of its children's.
  std::function<double(uint32_t, double)> cost = [&](uint32_t i, double a) -> double {
    double c = 1.0;
    for (int k = 0; k < CLPT_BVH_WIDTH; ++k) {
      if (area(n[i], k) == 0 && n[i].lower_x[k] > n[i].upper_x[k]) continue;  // empty slot
      const double child = n[i].count[k] != 0 ? double(((n[i].count[k] & CLPT_BVH_COUNT_MASK) + 3u) / 4u)
                                              : cost(n[i].child[k], area(n[i], k));
      c += area(n[i], k) * child / a;
    }
    return c;
  };
  GpuBvhNode root = n[0];
  float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (int k = 0; k < CLPT_BVH_WIDTH; ++k) {
    if (root.lower_x[k] > root.upper_x[k]) continue;
    lo[0] = std::min(lo[0], root.lower_x[k]), lo[1] = std::min(lo[1], root.lower_y[k]), lo[2] = std::min(lo[2], root.lower_z[k]);
    hi[0] = std::max(hi[0], root.upper_x[k]), hi[1] = std::max(hi[1], root.upper_y[k]), hi[2] = std::max(hi[2], root.upper_z[k]);
  }
  const double x = double(hi[0]) - lo[0], y = double(hi[1]) - lo[1], z = double(hi[2]) - lo[2];
  const double root_cost = cost(0, x * y + y * z + z * x);
  EXPECT_NEAR(bvh_sah_cost(ds.bvh), root_cost, 1e-9 * root_cost);
  // A binned SAH tree over 2000 triangles costs far less than testing them all.
  EXPECT_LT(bvh_sah_cost(ds.bvh), 100.0);
}

GpuTriangle triangle_at_z(float z) {
  GpuTriangle t{};
  const float v[3][3] = {{0, 0, z}, {1, 0, z}, {0, 1, z}};
  std::memcpy(t.v0, v[0], sizeof t.v0);
  std::memcpy(t.v1, v[1], sizeof t.v1);
  std::memcpy(t.v2, v[2], sizeof t.v2);
  return t;
}

// Two leaves along z, one triangle each (z = 0.5 and z = 2.5, the corner x, y in [0, 1], x + y <= 1),
// the root's slots 0 and 1.
DeviceScene two_leaf_scene() {
  DeviceScene ds;
  ds.triangles = {triangle_at_z(0.5f), triangle_at_z(2.5f)};
  ds.bvh.nodes = {node({{{0, 0, 0}, {1, 1, 1}, 0, 1}, {{0, 0, 2}, {1, 1, 3}, 1, 1}})};
  return ds;
}

StatsRay ray(std::array<double, 3> o, std::array<double, 3> d) {
  StatsRay r;
  r.origin = o;
  r.direction = d;
  return r;
}

TEST(BvhStats, ReplicaCountsTheKernelsOrderOnATinyTree) {
  const DeviceScene ds = two_leaf_scene();
  {
    // +z: the root opened (two occupied slots tested), both hit, the nearer (slot 0) visited in the
    // same iteration: its triangle at t = 1.5; slot 1 popped, its box tested again (entry 3 > 1.5)
    // and not visited.
    TraversalCounts c;
    const StatsHit h = replica_closest_hit(ds, ray({0.25, 0.25, -1}, {0, 0, 1}), c);
    EXPECT_EQ(h.triangle, 0);
    EXPECT_DOUBLE_EQ(h.t, 1.5);
    EXPECT_EQ(c.nodes, 2u);
    EXPECT_EQ(c.boxes, 3u);
    EXPECT_EQ(c.triangles, 1u);
    EXPECT_EQ(c.hits, 1u);
  }
  {
    // -z from above: slot 1 is nearer now.
    TraversalCounts c;
    const StatsHit h = replica_closest_hit(ds, ray({0.25, 0.25, 4}, {0, 0, -1}), c);
    EXPECT_EQ(h.triangle, 1);
    EXPECT_DOUBLE_EQ(h.t, 1.5);
    EXPECT_EQ(c.nodes, 2u);
    EXPECT_EQ(c.boxes, 3u);
    EXPECT_EQ(c.triangles, 1u);
  }
  {
    // Through both boxes, beside both triangles (x + y > 1): both leaves tested.
    TraversalCounts c;
    const StatsHit h = replica_closest_hit(ds, ray({0.9, 0.9, -1}, {0, 0, 1}), c);
    EXPECT_FALSE(h.hit());
    EXPECT_EQ(c.nodes, 2u);
    EXPECT_EQ(c.boxes, 3u);
    EXPECT_EQ(c.triangles, 2u);
    EXPECT_EQ(c.hits, 0u);
  }
  {
    // Only the lower box (leaving its y range at z = 0.5, beside the triangle there): the root
    // opened and slot 0's leaf tested, then nothing to pop.
    TraversalCounts c;
    EXPECT_FALSE(replica_closest_hit(ds, ray({0.25, 0.25, -1}, {0, 0.5, 1}), c).hit());
    EXPECT_EQ(c.nodes, 1u);
    EXPECT_EQ(c.boxes, 2u);
    EXPECT_EQ(c.triangles, 1u);
  }
  {
    // Beside both boxes: the root opened, its two boxes missed.
    TraversalCounts c;
    replica_closest_hit(ds, ray({5, 5, -1}, {0, 0, 1}), c);
    EXPECT_EQ(c.nodes, 1u);
    EXPECT_EQ(c.boxes, 2u);
    EXPECT_EQ(c.triangles, 0u);
    EXPECT_EQ(c.rays, 1u);
  }
}

TEST(BvhStats, RaySampleIsDeterministicAndSeesTheCornellBox) {
  const std::string file = std::string(CLPT_SOURCE_DIR) + "/scenes/cornell-box.toml";
  const Scene scene = load_scene_file(file);
  const DeviceScene ds = make_device_scene(scene, 64, 48);
  const StatsRaySample a = stats_rays(ds, 64, 48, 768), b = stats_rays(ds, 64, 48, 768);
  // stride ceil(sqrt(3072 / 768)) = 2: 32 x 24 camera rays.
  EXPECT_EQ(a.camera_rays, 32u * 24u);
  ASSERT_EQ(a.rays.size(), b.rays.size());
  EXPECT_GT(a.rays.size(), a.camera_rays);  // bounce rays from the hits
  EXPECT_EQ(std::memcmp(a.rays.data(), b.rays.data(), a.rays.size() * sizeof(StatsRay)), 0);
  const TraversalStats s = measure_traversal(ds, a);
  EXPECT_EQ(s.camera.rays, a.camera_rays);
  EXPECT_EQ(s.bounce.rays, a.rays.size() - a.camera_rays);
  // The box fills most of the view (the rest is the dark outside), and is closed but for its front:
  // most bounce rays hit a wall.
  EXPECT_GT(s.camera.hits, s.camera.rays / 2);  // 529 of 768 at 64x48 (a wider image than the box)
  EXPECT_GT(s.bounce.hits, s.bounce.rays / 2);
  const TraversalCounts all = s.all();
  EXPECT_GE(all.per_ray(all.nodes), 1.0);
  EXPECT_GE(all.per_ray(all.triangles), 1.0);
  EXPECT_LE(all.per_ray(all.triangles), double(ds.triangles.size()));
}

TEST(BvhBuild, SameTreeForAnyThreadCount) {
  // Enough primitives for parallel subtrees and a parallel binning pass at the root.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-10, 10), size(0.001f, 0.2f);
  std::vector<BvhPrimitive> prims;
  for (uint32_t i = 0; i < 150000; ++i) {
    BvhPrimitive p;
    p.index = i;
    // Clustered, with some spheres, so that the tree is uneven and has leaves of both kinds.
    const float cx = u(rng) * (i % 3 == 0 ? 0.1f : 1.0f), cy = u(rng), cz = u(rng) * 0.5f, s = size(rng);
    p.box.lower = {cx - s, cy - s, cz - s};
    p.box.upper = {cx + s, cy + s, cz + s};
    p.kind = i % 17 == 0 ? PrimitiveKind::Sphere : PrimitiveKind::Triangle;
    prims.push_back(p);
  }
  BvhBuildOptions one;
  one.threads = 1;
  const Bvh reference = build_bvh(prims, one);
  ASSERT_GT(reference.nodes.size(), 1000u);
  for (int threads : {2, 3, 8}) {
    SCOPED_TRACE(threads);
    BvhBuildOptions o;
    o.threads = threads;
    const Bvh b = build_bvh(prims, o);
    EXPECT_EQ(b.build_threads, threads);
    ASSERT_EQ(b.nodes.size(), reference.nodes.size());
    EXPECT_EQ(std::memcmp(b.nodes.data(), reference.nodes.data(), b.nodes.size() * sizeof(GpuBvhNode)), 0);
    EXPECT_EQ(b.triangle_order, reference.triangle_order);
    EXPECT_EQ(b.sphere_order, reference.sphere_order);
    EXPECT_EQ(b.depth, reference.depth);
    EXPECT_EQ(b.binary_depth, reference.binary_depth);
    EXPECT_EQ(b.stack_need, reference.stack_need);
  }
}

DeviceInfo device_of(bool cpu) {
  DeviceInfo d;
  d.name = cpu ? "test CPU" : "test GPU";
  d.is_cpu = cpu;
  d.is_gpu = !cpu;
  return d;
}

TEST(FormRule, PicksTheWavefrontOnCpusForMeshOnlyScenes) {
  KernelFeatures spheres;
  spheres.triangles = false;
  spheres.sphere_count = 8;
  KernelFeatures sphere_tree = spheres;
  sphere_tree.spheres_in_bvh = true;
  sphere_tree.sphere_count = 7;  // the large ones stay in the loop
  KernelFeatures mesh_in_room;
  mesh_in_room.triangles = true;
  mesh_in_room.sphere_count = 6;
  KernelFeatures mesh_only;
  mesh_only.triangles = true;
  mesh_only.sphere_count = 0;
  EXPECT_EQ(scene_geometry(spheres), SceneGeometry::LoopSpheres);
  EXPECT_EQ(scene_geometry(sphere_tree), SceneGeometry::SphereHierarchy);
  EXPECT_EQ(scene_geometry(mesh_in_room), SceneGeometry::MeshesAndSpheres);
  EXPECT_EQ(scene_geometry(mesh_only), SceneGeometry::MeshesOnly);
  KernelFeatures walls_and_model = mesh_only;  // the loop's meshes of large triangles beside a hierarchy
  walls_and_model.loop_triangles = 12;
  walls_and_model.hierarchy_triangles = true;
  EXPECT_EQ(scene_geometry(walls_and_model), SceneGeometry::LoopMeshesAndHierarchy);
  KernelFeatures all_in_loop = walls_and_model;  // the Cornell box: every triangle in the loop
  all_in_loop.loop_triangles = 32;
  all_in_loop.hierarchy_triangles = false;
  EXPECT_EQ(scene_geometry(all_in_loop), SceneGeometry::MeshesOnly);
  const DeviceInfo cpu = device_of(true), gpu = device_of(false);
  EXPECT_EQ(default_form_for(cpu, spheres).form, ExecutionForm::Megakernel);
  EXPECT_EQ(default_form_for(cpu, sphere_tree).form, ExecutionForm::Megakernel);
  EXPECT_EQ(default_form_for(cpu, mesh_in_room).form, ExecutionForm::Megakernel);
  EXPECT_EQ(default_form_for(cpu, mesh_only).form, ExecutionForm::Wavefront);
  EXPECT_NE(default_form_for(cpu, mesh_only).reason.find("meshes only"), std::string::npos);
  EXPECT_EQ(default_form_for(cpu, walls_and_model).form, ExecutionForm::Megakernel);
  EXPECT_EQ(default_form_for(cpu, all_in_loop).form, ExecutionForm::Wavefront);
  for (const KernelFeatures& f : {spheres, sphere_tree, mesh_in_room, mesh_only, walls_and_model})
    EXPECT_EQ(default_form_for(gpu, f).form, ExecutionForm::Megakernel);
}

TEST(FormRule, ThePlanTakesTheRuleUnlessFormIsGiven) {
  RenderRequest request;
  request.scene = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/cornell-box.toml");
  const DeviceInfo cpu = device_of(true);
  RenderPlan plan = plan_render(request, {cpu});
  EXPECT_EQ(plan.devices.front().form, ExecutionForm::Wavefront);
  EXPECT_NE(plan.devices.front().form_reason.find("meshes only"), std::string::npos);
  EXPECT_NE(explain_plan(plan).find("execution form: wavefront (the default on a CPU"), std::string::npos);
  // The generic kernel has every feature compiled, but the rule reads the scene's geometry.
  request.generic_kernel = true;
  EXPECT_EQ(plan_render(request, {cpu}).devices.front().form, ExecutionForm::Wavefront);
  request.form = ExecutionForm::Megakernel;
  plan = plan_render(request, {cpu});
  EXPECT_EQ(plan.devices.front().form, ExecutionForm::Megakernel);
  EXPECT_EQ(plan.devices.front().form_reason, "--form");
  request = RenderRequest();
  request.scene = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/diffuse.toml");
  EXPECT_EQ(plan_render(request, {cpu}).devices.front().form, ExecutionForm::Megakernel);
}

// PoCL compiles a kernel per work-group size and per grid width class (cl_device.h): the plan
// keeps every launch of a render on one of each, and stores no PoCL binaries in clpt's cache.
TEST(RenderPlanOnPocl, OneCompiledKernelPerStageAndNoBinaryCache) {
  RenderRequest request;
  request.scene = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/diffuse.toml");
  request.megakernel_loop = MegakernelLoop::PerPath;
  DeviceInfo pocl = device_of(true);
  pocl.platform_name = kPoclPlatformName;
  pocl.compute_units = 64;  // 64 x 32768 paths would be the wavefront's pool elsewhere
  DeviceInfo other = device_of(true);
  other.compute_units = 64;
  ASSERT_EQ(pocl.uniform_launch_limit(), 64512u);
  ASSERT_EQ(other.uniform_launch_limit(), 0u);

  RenderPlan plan = plan_render(request, {pocl, other});
  const DevicePlan& p = plan.devices[0];
  const DevicePlan& o = plan.devices[1];
  EXPECT_EQ(p.local_size, MegakernelRenderer::kPartialLaunchLocalSize);  // not the driver's choice
  EXPECT_EQ(p.sizing.max_jobs, 64512u);
  EXPECT_EQ(o.local_size, 0u);
  EXPECT_EQ(o.sizing.max_jobs, UINT32_MAX);
  EXPECT_FALSE(p.kernel_cache);
  EXPECT_TRUE(o.kernel_cache);
  EXPECT_NE(explain_plan(plan).find("kernel cache: the driver's own"), std::string::npos);
  EXPECT_NE(explain_plan(plan).find("and 64512 paths (the driver's one compiled kernel)"), std::string::npos);

  request.form = ExecutionForm::Wavefront;
  plan = plan_render(request, {pocl, other});
  EXPECT_EQ(plan.devices[0].paths_in_flight, 64512u);
  EXPECT_EQ(plan.devices[1].paths_in_flight, 64u * 32768u);
  EXPECT_EQ(plan.devices[0].sizing.max_jobs, UINT32_MAX);  // the pool bounds the stage launches
  request.use_kernel_cache = false;  // --no-cache: off everywhere, and nothing more to say
  plan = plan_render(request, {pocl, other});
  EXPECT_FALSE(plan.devices[1].kernel_cache);
  EXPECT_EQ(explain_plan(plan).find("kernel cache: the driver's own"), std::string::npos);
}

// clpt bench's traversal-alone rate (tools/traversal_trace.h, kernels/trace.cl): its kernel answers
// the sample's rays as the host's replica does, through a small mesh's triangle loop (the
// specialised kernel of the Cornell box) and through the hierarchy (the generic kernel), and
// reports a rate.
TEST(TraversalTrace, HitsWhatTheReplicaHitsInBothWays) {
  RenderRequest request;
  request.scene = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/cornell-box.toml");
  const DeviceInfo& device = test_device().device();
  const DeviceScene ds = make_device_scene(request.scene, 32, 24);
  ASSERT_EQ(ds.loop_spheres, 0u);  // the replica's hits are then the triangles' alone, as the trace's
  // The camera rays alone: a bounce ray's origin, rounded to float for the device, can land behind
  // the surface it leaves by less than the sample's offset, and the device then finds that surface
  // at a tiny distance where the double replica does not (renders offset by the hit's error bound,
  // triangle.cl; the bench's rates include those few extra hits alike for Embree and clpt).
  StatsRaySample sample = stats_rays(ds, 32, 24);
  sample.rays.resize(sample.camera_rays);
  const TraversalStats replica = measure_traversal(ds, sample);
  const uint64_t replica_hits = replica.camera.hits;
  ASSERT_GT(replica_hits, sample.rays.size() / 2);
  for (const bool generic : {false, true}) {
    request.generic_kernel = generic;
    const RenderPlan plan = plan_render(request, {device});
    const KernelFeatures& features = plan.devices.front().features;
    // The loop is the specialised kernel's on PoCL's CPU device with its 16 lanes set (AVX-512
    // hosts); elsewhere (an AVX2 host, the generic kernel) the hierarchy.
    if (device.is_cpu && device.platform_name == kPoclPlatformName && features.cpu_vector_lanes > 0) {
      EXPECT_EQ(features.triangles_in_loop(), !generic);
    }
    if (generic) {
      EXPECT_FALSE(features.triangles_in_loop());
    }
    const TraceRates t = time_clpt_trace(device, features, ds, make_params(request.scene, ds), sample, 0.0);
    SCOPED_TRACE(generic ? "generic kernel (hierarchy)" : "specialised kernel");
    EXPECT_EQ(t.rays, sample.rays.size());
    // The replica is double precision; a ray grazing an edge may go either way.
    EXPECT_NEAR(double(t.hits), double(replica_hits), 0.01 * double(sample.rays.size()) + 1);
    EXPECT_GE(t.launch_rays, t.rays);
    EXPECT_GT(t.per_s, 0);
    EXPECT_GT(t.per_cpu_s, 0);
  }
}

// The same for spheres in the hierarchy (the anchor's sphere rows): 40 balls alone in the book's
// camera view, too many for the loop, so that every one is a hierarchy primitive and the replica's
// hits are the hierarchy's alone, as the trace's. Camera rays and their bounces: a bounce ray leaves
// a ball from the scene's ray epsilon, as trace.cl's sphere tests start, so it may hit another.
TEST(TraversalTrace, HitsWhatTheReplicaHitsOnSpheresInTheHierarchy) {
  RenderRequest request;
  request.scene = load_scene_file(std::string(CLPT_SOURCE_DIR) + "/scenes/diffuse.toml");
  const Material material = request.scene.spheres.front().material;
  request.scene.spheres.clear();
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> along(-2.5, 3.5), across(-2.5, 2.5), size(0.2, 0.5);
  for (int i = 0; i < 40; ++i) {
    Sphere ball;
    ball.name = "ball" + std::to_string(i);
    ball.radius = size(rng);
    ball.center = {along(rng), ball.radius + 0.5 * size(rng), across(rng)};
    ball.material = material;
    request.scene.spheres.push_back(ball);
  }
  const DeviceInfo& device = test_device().device();
  const DeviceScene ds = make_device_scene(request.scene, 32, 24);
  ASSERT_EQ(ds.loop_spheres, 0u);
  ASSERT_EQ(ds.bvh.sphere_order.size(), 40u);
  const StatsRaySample sample = stats_rays(ds, 32, 24);
  const TraversalStats replica = measure_traversal(ds, sample);
  const uint64_t replica_hits = replica.camera.hits + replica.bounce.hits;
  ASSERT_GT(replica.camera.hits, sample.camera_rays / 10);  // the balls fill a good part of the view
  const RenderPlan plan = plan_render(request, {device});
  const TraceRates t = time_clpt_trace(device, plan.devices.front().features, ds, make_params(request.scene, ds), sample, 0.0);
  EXPECT_EQ(t.rays, sample.rays.size());
  EXPECT_NEAR(double(t.hits), double(replica_hits), 0.01 * double(sample.rays.size()) + 1);
  EXPECT_GT(t.per_s, 0);
}

}  // namespace
}  // namespace clpt::test
