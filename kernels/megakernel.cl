/* megakernel.cl: the megakernel execution form.
 *
 * One work-item per path (job) of the launch: job j traces sample job_sample(j) of pixel
 * job_pixel(j) (film.cl: a pixel range, or an adaptive pass's slots). It runs the stages of
 * path.cl in a loop, one segment per iteration, until the path ends, and leaves its result for
 * film_sum_jobs (film.cl). Reads: the geometry (spheres; the hierarchy and triangles, bvh.cl),
 * GpuRenderParams, the light buffer (nee) and the slots (adaptive passes). Writes: results (and,
 * with CLPT_AOVS, the job's first-hit layers after them: film_aov.cl).
 *
 * Two loops, chosen by the host (kernel_options.cpp, CLPT_LOCKSTEP_GROUP):
 *  - per path (GPUs): each work-item loops until its own path ends; the GPU's SIMT hardware masks
 *    the lanes whose paths have ended.
 *  - lockstep (CPUs): the paths of a work-group of CLPT_LOCKSTEP_GROUP work-items advance one
 *    segment per iteration together, with a barrier per segment, until all of them have ended;
 *    a path that has ended keeps its state (path_select) while the others go on. PoCL vectorises
 *    a kernel across work-items only in loop-free code between barriers: the per-path loop stays
 *    scalar on a CPU, while the lockstep body runs 8 paths per AVX instruction (measured 5x the
 *    per-path loop's paths/s; README "Speed"). The price is the lanes of ended paths, a few per
 *    cent on the book's scenes where nearly every path runs to the depth limit. */
#include "types.h"
#include "path.cl"
#include "film.cl"
#if defined(CLPT_AOVS) && CLPT_AOVS
#include "film_aov.cl" /* the first-hit layers' results and sums */
#endif

#ifndef CLPT_LOCKSTEP_GROUP
#define CLPT_LOCKSTEP_GROUP 0
#endif
/* Whether the lockstep loop pairs segments under one draw (kernel_options.cpp,
 * lockstep_pairs_segments): named, as 0, only where the triangle loop keeps it one a step. */
#ifndef CLPT_LOCKSTEP_SEGMENT_PAIRS
#define CLPT_LOCKSTEP_SEGMENT_PAIRS 1
#endif
#if CLPT_LOCKSTEP_GROUP
/* Contract: launched with work-groups of exactly CLPT_LOCKSTEP_GROUP work-items and a global size
 * rounded up to a whole number of them; the work-items past the last job trace a dead copy of
 * job 0 and store nothing. The barriers around alive_of keep its store out of the shading region:
 * an address computed once and kept across a barrier becomes a 64-bit value in that region, which
 * halves the width PoCL vectorises it with. */
__kernel void render_paths(__global const GpuSphere* spheres, __global const GpuLight* lights,
                           __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                           __global const GpuTriangleShading* triangle_shading, __global const GpuEnvironment* environment,
                           __global const uchar* texturing,
                           const GpuRenderParams params, __global const GpuSampleSlot* slots,
                           __global float* results) {
  __local uint alive_of[CLPT_LOCKSTEP_GROUP];
  __local uint any_alive;
#if CLPT_NO_FAST_GATHER
  /* On CPUs without fast gathers (kernel_options.cpp, docs/performance.md "CPUs without fast
   * gathers") the paths' state between segments goes through local memory, field by field
   * (path_state.h), rather than in variables carried round the loop. Why: PoCL runs LLVM's SLP
   * vectoriser on each work-item's code before it builds the work-item loops; the loop-carried
   * fields are PHI nodes of one type whose updates (path_select, v3_select) all have one shape,
   * and with those CPUs' costs SLP packs four of them (origin x, y, z and direction x) into a
   * <4 x float> PHI, and a work-item loop holding a vector-typed value is not vectorised at all.
   * Through memory, with barriers between the store and the load, no PHI is left to pack. PoCL
   * keeps values live across barriers in per-work-item arrays anyway, so the state costs about
   * what it did: a load and a store per field and segment, contiguous across the work-items. */
#define CLPT_LOCKSTEP_STATE(type, name, bytes, doc) __local type name[CLPT_LOCKSTEP_GROUP];
  CLPT_PATH_FIELDS(CLPT_PATH_BUFFERS_OF, CLPT_LOCKSTEP_STATE) /* the wavefront's buffers, but the job index */
#undef CLPT_LOCKSTEP_STATE
#endif
  const SceneBuffers scene = scene_buffers(spheres, lights, nodes, triangles, triangle_shading, environment, texturing);
  const uint jobs = job_count(&params);
  const uint job = (uint)get_global_id(0);
  const uint lid = (uint)get_local_id(0);
  const bool active = job < jobs;
  const uint j = active ? job : 0u;
  const uint pixel = job_pixel(&params, slots, j);
  const uint sample = job_sample(&params, slots, j);
  PathState path = path_begin(&params, pixel, sample);
  path.alive = active ? 1 : 0;
  /* Always 0, but carried round the loop from a value the compiler cannot know (any_alive >> 1,
   * any_alive being 1 where it is read): addresses of the form lid + slot_offset are then computed
   * afresh each segment next to their use. Computed once before the loop, they would be pointers
   * kept across the barriers, which PoCL stores per work-item as 64-bit values, and on CPUs
   * without 512-bit registers a 64-bit value halves the width the work-item loops are vectorised
   * with (8 -> 4 floats). */
  uint slot_offset = 0u;
  for (;;) {
    PathState next = path;
#if CLPT_HAS_BVH
    /* A traversal loop runs scalar (it is data dependent); barriers keep each in a region of its
     * own (the closest hit, then nee's shadow ray), so the sphere loop and the shading between
     * them still run vectorised across paths. path_shade's halves, as path.cl composes them. */
    Hit hit = path_intersect_loop(&path, &scene, &params);
    hit.t = path.alive ? hit.t : (real)0; /* an ended path's traversal stops at the root's box */
    barrier(CLK_LOCAL_MEM_FENCE);
    path_intersect_hierarchy(&path, &scene, &params, &hit);
    barrier(CLK_LOCAL_MEM_FENCE);
    ShadowQuery shadow;
    path_shade_surface(&next, hit, &scene, &params, &shadow);
#if CLPT_NEE_COMPILED
    shadow.t_max = path.alive ? shadow.t_max : (real)0; /* likewise for its shadow ray */
    barrier(CLK_LOCAL_MEM_FENCE);
    const bool blocked = shadow_query_blocked(&shadow, &scene, &params);
    barrier(CLK_LOCAL_MEM_FENCE);
#else
    const bool blocked = false;
#endif
    path_shade_light(&next, &shadow, blocked);
    path = path_select(path.alive != 0, next, path);
#elif defined(CLPT_SCATTER_DRAW_PAIRS) && CLPT_SCATTER_DRAW_PAIRS && CLPT_UNROLL_SCENE_LOOPS && CLPT_LOCKSTEP_SEGMENT_PAIRS
    /* Two segments per step, one draw for both (path.cl, scatter_draw): every live path of the
     * group is at the same bounce, an even one here, as all start at 0 and each live path's
     * segment adds one (a segment that does not scatter ends the path). Ended paths' lanes compute
     * with their own state and are selected away. Only with the unrolled scene loops, the CPUs'
     * shape: a forced lockstep kernel on a GPU (rolled loops) keeps one segment a step, whose
     * registers two would raise (gfx906: 110 -> 127 VGPRs, scripts/gpu_compile.sh); and not with
     * the triangle loop, whose four unrolled copies doubled PoCL's cold compile (12 s for the
     * Cornell box; docs/performance.md, "Fixed costs"). */
    const Uniform4 draw = scatter_draw(&params, &path);
    path_shade_drawn(&next, path_intersect(&path, &scene, &params), &scene, &params, draw);
    path = path_select(path.alive != 0, next, path);
    next = path;
    path_shade_drawn(&next, path_intersect(&path, &scene, &params), &scene, &params, draw);
    path = path_select(path.alive != 0, next, path);
#else
    path_shade(&next, path_intersect(&path, &scene, &params), &scene, &params);
    path = path_select(path.alive != 0, next, path);
#endif
    barrier(CLK_LOCAL_MEM_FENCE);
#if CLPT_NO_FAST_GATHER
    {
      const uint slot = lid + slot_offset;
      const PathState* p = &path;
      CLPT_PATH_STORE_FIELDS
    }
#endif
    alive_of[lid + slot_offset] = (uint)path.alive;
    barrier(CLK_LOCAL_MEM_FENCE);
    if (lid == 0u) {
      uint any = 0u;
      for (uint k = 0u; k < CLPT_LOCKSTEP_GROUP; ++k) any |= alive_of[k];
      any_alive = any;
    }
    barrier(CLK_LOCAL_MEM_FENCE);
    if (any_alive == 0u) break;
    slot_offset = any_alive >> 1;
#if CLPT_NO_FAST_GATHER
    {
      const uint slot = lid + slot_offset;
      PathState p;
      CLPT_PATH_LOAD_FIELDS
      p.pixel = pixel;
      p.sample = sample;
      p.alive = (int)alive_of[slot];
      path = p;
    }
#endif
  }
  /* The job index afresh (not `job`, which kept across the loop would be a 64-bit value). */
  const uint job_done = (uint)get_global_id(0) + slot_offset;
  if (job_done < jobs) job_result_store(results, job_done, jobs, path.radiance, path.segments);
#if defined(CLPT_AOVS) && CLPT_AOVS
  if (job_done < jobs) job_aov_store(results, job_done, jobs, &path);
#endif
}
#else
__kernel void render_paths(__global const GpuSphere* spheres, __global const GpuLight* lights,
                           __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                           __global const GpuTriangleShading* triangle_shading, __global const GpuEnvironment* environment,
                           __global const uchar* texturing,
                           const GpuRenderParams params, __global const GpuSampleSlot* slots,
                           __global float* results) {
  const SceneBuffers scene = scene_buffers(spheres, lights, nodes, triangles, triangle_shading, environment, texturing);
  const uint job = (uint)get_global_id(0);
  if (job >= job_count(&params)) return;
  PathState path = path_begin(&params, job_pixel(&params, slots, job), job_sample(&params, slots, job));
  while (path.alive) {
    path_shade(&path, path_intersect(&path, &scene, &params), &scene, &params);
  }
  job_result_store(results, job, job_count(&params), path.radiance, path.segments);
#if defined(CLPT_AOVS) && CLPT_AOVS
  job_aov_store(results, job, job_count(&params), &path);
#endif
}
#endif
