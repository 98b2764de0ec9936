// Statistics of a device scene's hierarchy, on the host: its SAH cost, and the nodes and
// primitives a ray visits, counted by a double-precision replica of the kernels' traversal
// (kernels/bvh.cl, bvh_traverse: the same stack discipline over the 4-wide nodes, the nearest hit
// child first, the others pushed farthest first and their boxes tested again when popped) over a
// deterministic sample of rays (stats_rays).
// `clpt bench` reports them for every row with a hierarchy (docs/performance.md, "Traversal").
// The replica decides the same boxes in double that the kernels decide in float, so its counts
// are those of the kernels' order up to rays that graze a box; it is no renderer (no shading).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scene/bvh_build.h"
#include "scene/device_scene.h"

namespace clpt {

// The SAH cost of `bvh` by its own boxes, in units of one primitive test: the sum over its 4-wide
// nodes of traversal_cost * A(node) / A(root) (a node's box: the union of its children's; one
// test of its four boxes costs traversal_cost) plus the sum over leaves of tests * A(leaf) /
// A(root) (A: surface area; tests: the leaf's count in groups of bvh.leaf_group, as its builder
// charged them, e.g. blocks of four triangles), the expected cost of a ray through the root under
// the heuristic's assumptions. 0 with no nodes or a root of no area.
double bvh_sah_cost(const Bvh& bvh, double traversal_cost = 1.0);

// A ray in the kernels' camera-relative coordinates; `direction` need not be unit. `t_min` is the
// spheres' minimum distance (the kernels' ray epsilon; triangles are hit at any t > 0).
struct StatsRay {
  std::array<double, 3> origin{}, direction{};
  double t_min = 0;
};

// What one closest-hit query cost: nodes visited (iterations of bvh_traverse's loop: a 4-wide node
// opened, its four boxes in one test and, when its nearest hit child is a leaf, that leaf's
// primitives tested in the same iteration; or an entry popped from the stack, its box tested
// again, then its leaf tested or its node opened in the next iteration), box tests (a node's
// occupied child slots, and each popped entry's), triangle and sphere tests in leaves. The loop's
// spheres (DeviceScene::loop_spheres) are tested before the hierarchy, as the kernels do, and
// count as sphere tests too; with `triangle_loop`, the loop's triangles likewise (loop_triangles).
struct TraversalCounts {
  uint64_t rays = 0, hits = 0;
  uint64_t nodes = 0, boxes = 0, triangles = 0, hierarchy_spheres = 0, loop_spheres = 0, loop_triangles = 0;
  void add(const TraversalCounts& o);
  double per_ray(uint64_t n) const { return rays ? double(n) / double(rays) : 0; }
};

// The closest hit as the replica finds it: t (infinity: none), and the hit sphere or triangle
// (indices as in the device buffers; -1: none).
struct StatsHit {
  double t = 0;
  int sphere = -1, triangle = -1;
  bool hit() const { return sphere >= 0 || triangle >= 0; }
};

// The replica of scene_closest_hit (kernels/bvh.cl) for one ray, counting into `counts`.
// `triangle_loop`: as a kernel whose triangle loop tests the loop's meshes' triangles
// (DeviceScene::loop_triangles) before a traversal from node 1 (CLPT_BVH_ROOT=1,
// KernelFeatures::loop_beside_hierarchy); else the traversal from the root, as every other.
StatsHit replica_closest_hit(const DeviceScene& ds, const StatsRay& ray, TraversalCounts& counts,
                             bool triangle_loop = false);

// The sample of rays the statistics use, deterministic (no seed but the ray's index):
//  * camera rays: one through the centre of every `stride`-th pixel in each direction of a
//    width x height image, stride = ceil(sqrt(width * height / max_camera_rays)) (4096 rays or
//    fewer: 80x60 at 320x240);
//  * bounce rays: for every camera ray that hits something (replica_closest_hit), one ray from the
//    hit point (moved off the surface along its geometric normal, towards the camera's side, by
//    the scene's ray epsilon) in a cosine-distributed direction about that normal: a diffuse
//    bounce, with its two numbers from a SplitMix64 hash of the camera ray's index.
// Camera rays first, then the bounce rays in the same order.
struct StatsRaySample {
  std::vector<StatsRay> rays;
  size_t camera_rays = 0;  // rays[0 .. camera_rays) are camera rays, the rest bounce rays
};
StatsRaySample stats_rays(const DeviceScene& ds, int width, int height, size_t max_camera_rays = 4096);

// The averages over a sample: replica_closest_hit on every ray of `rays`.
struct TraversalStats {
  TraversalCounts camera, bounce;  // the two kinds of ray, apart
  TraversalCounts all() const;
};
TraversalStats measure_traversal(const DeviceScene& ds, const StatsRaySample& sample, bool triangle_loop = false);

}  // namespace clpt
