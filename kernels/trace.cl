/* trace.cl: closest-hit queries against a scene's triangles and hierarchy spheres alone, for
 * measuring the traversal.
 *
 * `clpt bench --traversal-anchor` times this kernel on the same rays and primitives as the anchor
 * (Embree's rtcIntersect1, which holds those alone: not the loop's spheres), so that the two rates
 * compare the same queries: a small mesh's triangle loop (triangle_loop.cl) or the hierarchy
 * (bvh.cl, scene_hierarchy_hit), as the renders call them, with no shading, no loop spheres and no
 * shadow rays around them. Built with the options of the bench row's render (kernel_options.cpp),
 * so it traverses exactly as that row's kernels do; renders never build it.
 *
 * rays[8i .. 8i + 2] = origin (camera-relative, as the device scene), rays[8i + 4 .. 8i + 6] = unit
 * direction, from t = 0 (triangles are intersected for t > 0, spheres past the scene's ray
 * epsilon); t_out[i] = the hit distance, or CLPT_NO_HIT. */
#include "types.h"
#include "bvh.cl"

__kernel void trace_hierarchy(__global const GpuSphere* spheres, __global const GpuLight* lights,
                              __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                              __global const GpuTriangleShading* triangle_shading,
                              __global const GpuEnvironment* environment, __global const uchar* texturing,
                              const GpuRenderParams params, __global const float* rays, uint count,
                              __global float* t_out) {
  /* No early return for the work-items past `count` (they trace the last ray again and store
   * nothing): a return is control flow that keeps PoCL from vectorising the triangle loop across
   * work-items. */
  const uint id = (uint)get_global_id(0);
  const uint i = id < count ? id : count - 1u;
  const SceneBuffers scene = scene_buffers(spheres, lights, nodes, triangles, triangle_shading, environment, texturing);
  /* Read as scalars: a float4 load is an instruction of vector type, which PoCL's work-item
   * vectoriser cannot widen (it left the triangle loop's kernel scalar). */
  __global const float* r = rays + 8 * i;
  const Vec3 o = v3((real)r[0], (real)r[1], (real)r[2]), d = v3((real)r[4], (real)r[5], (real)r[6]);
  Hit hit = no_hit();
#if defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0
  triangle_loop_hit(triangles, texturing, o, d, 0u, &hit);
#endif
  scene_hierarchy_hit(&scene, &params, o, d, -1, 0u, &hit);
  if (id < count) t_out[i] = (float)hit.t;
}
