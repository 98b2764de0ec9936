/* wavefront.cl: the split wavefront execution form.
 *
 * A pool of path slots lives in structure-of-arrays buffers (path_state.h); the active paths
 * always occupy slots [0, active_count) densely, so each kernel runs over exactly the paths that
 * need it and work-item i touches slot i:
 *   wf_generate   slots [active, active + fresh) <- new camera paths for the pass's next jobs
 *   wf_intersect  active paths -> hit_t, hit_sphere, hit_triangle
 *   wf_shade      active paths -> emission, next ray or end; an ended path leaves its radiance in
 *                 its job's result slot, a surviving one is stored densely into the other state
 *                 set (atomic appends): shading and compaction in one pass
 *   film_sum_jobs every pixel -> GpuPixelPass, summing its samples in sample order (film.cl)
 *   film_sum_aovs with CLPT_AOVS: every pixel's first-hit layers, likewise (film_aov.cl)
 * The physics is path.cl's: these kernels only load a PathState, call the same stage function
 * as the megakernel, and store it. Job j of a pass is sample job_sample(j) of pixel job_pixel(j)
 * (film.cl); its result depends on nothing else, so the image equals
 * the megakernel's up to float rounding whatever the slot order or the number of paths in flight. */
#include "types.h"
#include "path_state.h"
#include "path.cl"
#include "film.cl"
#if defined(CLPT_AOVS) && CLPT_AOVS
#include "film_aov.cl" /* the first-hit layers' results and sums */
#endif

#define CLPT_STATE_PARAM(type, name, bytes, doc) , __global type* name
#define CLPT_STATE_PARAMS CLPT_PATH_STATE_FIELDS(CLPT_STATE_PARAM)
#define CLPT_SCRATCH_PARAMS CLPT_PATH_SCRATCH_FIELDS(CLPT_STATE_PARAM)
#define CLPT_STATE_NAME(type, name, bytes, doc) , name
#define CLPT_STATE_ARGS CLPT_PATH_STATE_FIELDS(CLPT_STATE_NAME)
/* The compaction's destination set: the same fields with a `to_` prefix. */
#define CLPT_TO_PARAM(type, name, bytes, doc) , __global type* to_##name
#define CLPT_TO_PARAMS CLPT_PATH_STATE_FIELDS(CLPT_TO_PARAM)
#define CLPT_TO_NAME(type, name, bytes, doc) , to_##name
#define CLPT_TO_ARGS CLPT_PATH_STATE_FIELDS(CLPT_TO_NAME)

CLPT_INLINE PathState path_load(uint slot, const GpuRenderParams* params,
                                __global const GpuSampleSlot* sample_slots CLPT_STATE_PARAMS) {
  PathState p;
  CLPT_PATH_LOAD_FIELDS
  const uint j = job[slot];
  p.pixel = job_pixel(params, sample_slots, j);
  p.sample = job_sample(params, sample_slots, j);
  p.alive = 1;  /* only living paths are stored */
  return p;
}

CLPT_INLINE void path_store(uint slot, uint job_index, const PathState* p CLPT_STATE_PARAMS) {
  CLPT_PATH_STORE_FIELDS
  job[slot] = job_index;
}

/* Starts jobs job_begin + i in slots slot_begin + i, for i < count. */
__kernel void wf_generate(const GpuRenderParams params, __global const GpuSampleSlot* sample_slots, uint job_begin,
                          uint slot_begin, uint count CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint job_index = job_begin + i;
  const PathState p = path_begin(&params, job_pixel(&params, sample_slots, job_index),
                                 job_sample(&params, sample_slots, job_index));
  path_store(slot_begin + i, job_index, &p CLPT_STATE_ARGS);
}

/* Takes every scene buffer, as wf_shade does (the host binds them alike); reads only geometry. */
__kernel void wf_intersect(__global const GpuSphere* spheres, __global const GpuLight* lights,
                           __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                           __global const GpuTriangleShading* triangle_shading, __global const GpuEnvironment* environment,
                           __global const uchar* texturing, const GpuRenderParams params,
                           __global const GpuSampleSlot* sample_slots, uint count CLPT_SCRATCH_PARAMS CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const SceneBuffers scene = scene_buffers(spheres, lights, nodes, triangles, triangle_shading, environment, texturing);
  const PathState p = path_load(i, &params, sample_slots CLPT_STATE_ARGS);
  const Hit hit = path_intersect(&p, &scene, &params);
  hit_t[i] = hit.t;
  hit_sphere[i] = hit.sphere;
  hit_triangle[i] = hit.triangle;
}

/* Shading and compaction in one pass: every active path is shaded; an ended path writes its
 * job's result (job_result_store, film.cl) and a surviving one is stored densely into the other
 * state set. Storing the shaded path straight into its compacted slot costs the same as storing
 * it in place, and saves a separate compaction kernel re-reading and re-writing every survivor
 * (measured on PoCL: that kernel took as long as intersection and shading together).
 * Slots are reserved once per work-group: one global atomic per path made the cores fight over
 * the counter's cache line. The shading region holds no atomic and no store to a shared address,
 * so PoCL still vectorises it across work-items; work-item 0 then ranks the group's survivors
 * serially (a work-group is at most CLPT_WAVEFRONT_GROUP) and reserves their slots.
 * No work-item returns early, since every one must reach the barriers: the work-items past
 * `count` shade whatever their slot holds (the host allocates a work-group of slots beyond the
 * pool, so that every work-item loads its own slot, contiguously, instead of a gather from a
 * clamped index), as a miss, and store nothing. */
#ifndef CLPT_WAVEFRONT_GROUP
#define CLPT_WAVEFRONT_GROUP 1024
#endif
__kernel void wf_shade(__global const GpuSphere* spheres, __global const GpuLight* lights,
                       __global const GpuBvhNode* nodes, __global const GpuTriangle* triangles,
                       __global const GpuTriangleShading* triangle_shading, __global const GpuEnvironment* environment,
                       __global const uchar* texturing, const GpuRenderParams params,
                       __global const GpuSampleSlot* sample_slots, uint count, __global float* results,
                       __global volatile uint* survivors CLPT_SCRATCH_PARAMS CLPT_STATE_PARAMS CLPT_TO_PARAMS) {
  __local uint rank_of[CLPT_WAVEFRONT_GROUP]; /* survives (0/1), then the survivor's rank */
  __local uint group_base;
  const uint i = (uint)get_global_id(0);
  const uint lid = (uint)get_local_id(0);
  const bool active = i < count;
  const uint slot = i;
  PathState p = path_load(slot, &params, sample_slots CLPT_STATE_ARGS);
  Hit hit;
  hit.t = hit_t[slot];
  hit.sphere = active ? hit_sphere[slot] : -1;
  hit.triangle = active ? hit_triangle[slot] : -1;
  const SceneBuffers scene = scene_buffers(spheres, lights, nodes, triangles, triangle_shading, environment, texturing);
  path_shade(&p, hit, &scene, &params);
  const uint job_index = job[slot];
  if (active && !p.alive) job_result_store(results, job_index, job_count(&params), p.radiance, p.segments);
#if defined(CLPT_AOVS) && CLPT_AOVS
  if (active && !p.alive) job_aov_store(results, job_index, job_count(&params), &p);
#endif
  const bool survives = active && p.alive;
  rank_of[lid] = survives ? 1u : 0u;
  barrier(CLK_LOCAL_MEM_FENCE);
  if (lid == 0u) {
    uint n = 0u;
    const uint size = (uint)get_local_size(0);
    for (uint k = 0u; k < size; ++k) {
      const uint s = rank_of[k];
      rank_of[k] = n;
      n += s;
    }
    group_base = atomic_add(survivors, n);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (survives) path_store(group_base + rank_of[lid], job_index, &p CLPT_TO_ARGS);
}
