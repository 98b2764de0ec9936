/* wavefront.cl: the split wavefront execution form.
 *
 * A fixed pool of path slots lives in structure-of-arrays buffers (path_state.h). Each kernel runs
 * over a queue of slot indices, so it touches only the paths that need it:
 *   wf_generate   free slots   -> new camera paths for the next jobs    (appended to the active queue)
 *   wf_intersect  active queue -> hit_t, hit_sphere
 *   wf_shade      active queue -> emission, next ray or end; ended paths leave their radiance in
 *                                 the job's sample slot
 *   wf_compact    active queue -> next active queue and free queue (atomic appends)
 *   wf_film       every pixel  -> GpuPixelPass, summing its samples in sample order
 * The physics is path.cl's: these kernels only load a PathState, call the same stage function
 * as the megakernel, and store it. A job j of a pass is sample (sample_begin + j / pixel_count)
 * of pixel (pixel_begin + j % pixel_count); its result depends on nothing else, so the image equals
 * the megakernel's up to float rounding whatever the queue order or the number of paths in flight. */
#include "types.h"
#include "path_state.h"
#include "path.cl"
#include "film.cl"

#define CLPT_STATE_PARAM(type, name, bytes, doc) , __global type* name
#define CLPT_STATE_PARAMS CLPT_PATH_STATE_FIELDS(CLPT_STATE_PARAM)

/* Job result: rgb radiance and, in w, the segment count's bits. */
typedef float4 JobResult;

CLPT_INLINE PathState path_load(uint slot, const GpuRenderParams* params,
                                __global const float4* origin, __global const float4* direction,
                                __global const float4* throughput, __global const float4* radiance,
                                __global const uint4* ids) {
  PathState p;
  const uint4 id = ids[slot];
  p.origin = origin[slot].xyz;
  p.direction = direction[slot].xyz;
  p.throughput = throughput[slot].xyz;
  p.radiance = radiance[slot].xyz;
  p.pixel = params->pixel_begin + id.x % params->pixel_count;
  p.sample = params->sample_begin + id.x / params->pixel_count;
  p.bounce = id.y;
  p.segments = id.z;
  p.skip_sphere = (int)id.w - 1;
  p.alive = 1;
  return p;
}

CLPT_INLINE void path_store(uint slot, uint job, const PathState* p, __global float4* origin,
                            __global float4* direction, __global float4* throughput,
                            __global float4* radiance, __global uint4* ids) {
  origin[slot] = (float4)(p->origin, 0.0f);
  direction[slot] = (float4)(p->direction, 0.0f);
  throughput[slot] = (float4)(p->throughput, 0.0f);
  radiance[slot] = (float4)(p->radiance, 0.0f);
  ids[slot] = (uint4)(job, p->bounce, p->segments, (uint)(p->skip_sphere + 1));
}

/* Consumes free[free_begin + i] for i < count; writes active[active_begin + i]. */
__kernel void wf_generate(const GpuRenderParams params, uint job_begin, uint count,
                          __global const uint* free_slots, uint free_begin,
                          __global uint* active, uint active_begin CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = free_slots[free_begin + i];
  const uint job = job_begin + i;
  const PathState p = path_begin(&params, params.pixel_begin + job % params.pixel_count,
                                 params.sample_begin + job / params.pixel_count);
  path_store(slot, job, &p, origin, direction, throughput, radiance, ids);
  active[active_begin + i] = slot;
}

__kernel void wf_intersect(__global const GpuSphere* spheres, const GpuRenderParams params,
                           __global const uint* active, uint count CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = active[i];
  const PathState p = path_load(slot, &params, origin, direction, throughput, radiance, ids);
  const Hit hit = path_intersect(&p, spheres, &params);
  hit_t[slot] = hit.t;
  hit_sphere[slot] = hit.sphere;
}

__kernel void wf_shade(__global const GpuSphere* spheres, const GpuRenderParams params,
                       __global const uint* active, uint count, __global JobResult* results
                           CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = active[i];
  PathState p = path_load(slot, &params, origin, direction, throughput, radiance, ids);
  Hit hit;
  hit.t = hit_t[slot];
  hit.sphere = hit_sphere[slot];
  path_shade(&p, hit, spheres, &params);
  const uint job = ids[slot].x;
  path_store(slot, job, &p, origin, direction, throughput, radiance, ids);
  alive[slot] = p.alive;
  if (!p.alive) results[job] = (float4)(p.radiance, as_float(p.segments));
}

/* counters[0]: next active queue length, counters[1]: free queue length (both appended to). */
__kernel void wf_compact(__global const uint* active, uint count, __global uint* next_active,
                         __global uint* free_slots, __global volatile uint* counters
                             CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = active[i];
  if (alive[slot]) next_active[atomic_inc(&counters[0])] = slot;
  else free_slots[atomic_inc(&counters[1])] = slot;
}

/* One work-item per pixel of the pass: its samples summed in sample order, as the megakernel does. */
__kernel void wf_film(const GpuRenderParams params, __global const JobResult* results,
                      __global GpuPixelPass* pass) {
  const uint local_pixel = (uint)get_global_id(0);
  if (local_pixel >= params.pixel_count) return;
  PixelAccumulator acc = pixel_accumulator_new();
  for (uint s = 0; s < params.samples_per_pass; ++s) {
    const JobResult r = results[s * params.pixel_count + local_pixel];
    pixel_accumulator_add(&acc, r.xyz, as_uint(r.w));
  }
  film_write_pass(&pass[local_pixel], &acc);
}
