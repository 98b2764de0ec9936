// Which spheres the kernels test in their sphere loop and which are primitives of the bounding
// volume hierarchy: decided once, from the scene alone. The scene's conversion for the kernels
// (device_scene.h) puts the loop's spheres first and builds the hierarchy over the others; the
// kernels' specialisation (kernels/kernel_options.h) fixes the loop's count from the same answer.
#pragma once

#include <vector>

#include "scene/scene.h"

namespace clpt {

// Spheres are tested in an unrolled loop up to this many; a scene with more makes them primitives
// of the bounding volume hierarchy (kernels/bvh.cl), all but its few large ones (loop_spheres).
// The crossover is measured with `clpt bench` (docs/performance.md, "Traversal").
constexpr int kMaxLoopSpheres = 16;
// Whether the scene's spheres are hierarchy primitives (more than kMaxLoopSpheres of them).
bool spheres_in_hierarchy(const Scene& scene);
// Which spheres the kernels' loop tests (the others are hierarchy primitives): all of them when
// there are at most kMaxLoopSpheres; else those of radius at least 10x the median, at most 8 of
// them (the book's walls, light and balls among pebbles): a wall's box would cover every other
// box, so each ray would visit the wall's leaf on any path through the tree.
std::vector<bool> loop_spheres(const Scene& scene);

// A small mesh is tested the same way: a scene of at most this many triangles, whose spheres are
// all in the loop, has its triangles tested in an unrolled loop after the spheres, every path's
// against every triangle, and compiles no hierarchy traversal (kernels/triangle_loop.cl; where the
// scene loops are unrolled, i.e. on CPUs: kernel_options.cpp). The threshold keeps the unrolled
// body's cold PoCL build under 10 s on 2 cores (32 triangles: 6-7 CPU-s; 40: 9.4; 64: 17): the
// Cornell box fits; docs/performance.md, "Fixed costs" and "Traversal".
constexpr int kMaxLoopTriangles = 32;
// Which meshes' triangles the loop tests (loop_triangle_count of them in all): every mesh when the
// scene has at most kMaxLoopTriangles triangles; in a larger scene (whose spheres are all in the
// loop) the meshes of large triangles, as the spheres' walls: those whose mean triangle area is at
// least 100 times the median triangle's (a room's walls and floor, a ground plane, an area light
// around a detailed model), largest mean first, whole meshes while the loop has room. Their
// triangles would otherwise sit in leaves whose boxes span the scene, which nearly every ray
// visits. None when the spheres are hierarchy primitives.
std::vector<bool> loop_meshes(const Scene& scene);
// The triangle loop's choice in one pass over the triangles (the areas of a million take tens of
// milliseconds): the meshes (loop_meshes), their triangles (at most kMaxLoopTriangles), and
// whether some triangle is a hierarchy primitive in every kernel (not in the loop's meshes).
struct TriangleLoopChoice {
  std::vector<bool> meshes;
  int triangles = 0;
  bool hierarchy_triangles = false;
};
TriangleLoopChoice triangle_loop_choice(const Scene& scene);
int loop_triangle_count(const Scene& scene);   // triangle_loop_choice(scene).triangles
bool hierarchy_triangles(const Scene& scene);  // triangle_loop_choice(scene).hierarchy_triangles

}  // namespace clpt
