/* trace.cl: closest-hit queries against a scene's triangles alone, for measuring the traversal.
 *
 * `clpt bench --traversal-anchor` times this kernel on the same rays and triangles as the anchor
 * (Embree's rtcIntersect1, which holds the triangles alone), so that the two rates compare the
 * same queries: a small mesh's triangle loop (triangle_loop.cl) or the hierarchy (bvh.cl,
 * scene_hierarchy_hit), as the renders call them, with no shading, no loop spheres and no shadow
 * rays around them. Built with the options of the bench row's render
 * (kernel_options.cpp), so it traverses exactly as that row's kernels do; renders never build it.
 *
 * rays[2i] = origin (camera-relative, as the device scene), rays[2i + 1] = unit direction, both
 * from t = 0 (triangles are intersected for t > 0); t_out[i] = the hit distance, or
 * CLPT_NO_HIT. */
#include "types.h"
#include "bvh.cl"

__kernel void trace_hierarchy(__global const GpuSphere* spheres, __global const GpuLight* lights,
                              __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                              __global const GpuTriangleShading* triangle_shading,
                              __global const GpuEnvironment* environment, __global const uchar* texturing,
                              const GpuRenderParams params, __global const float4* rays, uint count,
                              __global float* t_out) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const SceneBuffers scene = scene_buffers(spheres, lights, nodes, triangles, triangle_shading, environment, texturing);
  const float4 o = rays[2 * i], d = rays[2 * i + 1];
  Hit hit = no_hit();
#if defined(CLPT_TRIANGLE_COUNT) && CLPT_TRIANGLE_COUNT > 0
  triangle_loop_hit(triangles, texturing, v3(o.x, o.y, o.z), v3(d.x, d.y, d.z), 0u, &hit);
#endif
  scene_hierarchy_hit(&scene, &params, v3(o.x, o.y, o.z), v3(d.x, d.y, d.z), -1, 0u, &hit);
  t_out[i] = (float)hit.t;
}
