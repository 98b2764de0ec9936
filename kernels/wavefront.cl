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
/* The state buffers, as arguments to path_load / path_store. */
#define CLPT_STATE_NAME(type, name, bytes, doc) , name
#define CLPT_STATE_ARGS CLPT_PATH_STATE_FIELDS(CLPT_STATE_NAME)

CLPT_INLINE PathState path_load(uint slot, const GpuRenderParams* params CLPT_STATE_PARAMS) {
  PathState p;
  const uint j = job[slot];
  p.origin = v3(origin_x[slot], origin_y[slot], origin_z[slot]);
  p.direction = v3(direction_x[slot], direction_y[slot], direction_z[slot]);
  p.throughput = v3(throughput_r[slot], throughput_g[slot], throughput_b[slot]);
  p.radiance = v3(radiance_r[slot], radiance_g[slot], radiance_b[slot]);
  p.pixel = params->pixel_begin + j % params->pixel_count;
  p.sample = params->sample_begin + j / params->pixel_count;
  p.bounce = bounce[slot];
  p.segments = segments[slot];
  p.skip_sphere = skip_sphere[slot];
  p.alive = 1;
  return p;
}

CLPT_INLINE void path_store(uint slot, uint job_index, const PathState* p CLPT_STATE_PARAMS) {
  origin_x[slot] = p->origin.x;
  origin_y[slot] = p->origin.y;
  origin_z[slot] = p->origin.z;
  direction_x[slot] = p->direction.x;
  direction_y[slot] = p->direction.y;
  direction_z[slot] = p->direction.z;
  throughput_r[slot] = p->throughput.x;
  throughput_g[slot] = p->throughput.y;
  throughput_b[slot] = p->throughput.z;
  radiance_r[slot] = p->radiance.x;
  radiance_g[slot] = p->radiance.y;
  radiance_b[slot] = p->radiance.z;
  job[slot] = job_index;
  bounce[slot] = p->bounce;
  segments[slot] = p->segments;
  skip_sphere[slot] = p->skip_sphere;
}

/* Consumes free[free_begin + i] for i < count; writes active[active_begin + i]. */
__kernel void wf_generate(const GpuRenderParams params, uint job_begin, uint count,
                          __global const uint* free_slots, uint free_begin,
                          __global uint* active, uint active_begin CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = free_slots[free_begin + i];
  const uint job_index = job_begin + i;
  const PathState p = path_begin(&params, params.pixel_begin + job_index % params.pixel_count,
                                 params.sample_begin + job_index / params.pixel_count);
  path_store(slot, job_index, &p CLPT_STATE_ARGS);
  active[active_begin + i] = slot;
}

__kernel void wf_intersect(__global const GpuSphere* spheres, const GpuRenderParams params,
                           __global const uint* active, uint count CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = active[i];
  const PathState p = path_load(slot, &params CLPT_STATE_ARGS);
  const Hit hit = path_intersect(&p, spheres, &params);
  hit_t[slot] = hit.t;
  hit_sphere[slot] = hit.sphere;
}

/* Ended paths write their job's result: radiance in results[4 job + 0..2], the segment count's
 * bits in results[4 job + 3]. */
__kernel void wf_shade(__global const GpuSphere* spheres, const GpuRenderParams params,
                       __global const uint* active, uint count, __global float* results
                           CLPT_STATE_PARAMS) {
  const uint i = (uint)get_global_id(0);
  if (i >= count) return;
  const uint slot = active[i];
  PathState p = path_load(slot, &params CLPT_STATE_ARGS);
  Hit hit;
  hit.t = hit_t[slot];
  hit.sphere = hit_sphere[slot];
  path_shade(&p, hit, spheres, &params);
  const uint job_index = job[slot];
  path_store(slot, job_index, &p CLPT_STATE_ARGS);
  alive[slot] = p.alive;
  if (!p.alive) {
    results[4 * job_index + 0] = p.radiance.x;
    results[4 * job_index + 1] = p.radiance.y;
    results[4 * job_index + 2] = p.radiance.z;
    results[4 * job_index + 3] = as_float(p.segments);
  }
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
__kernel void wf_film(const GpuRenderParams params, __global const float* results,
                      __global GpuPixelPass* pass) {
  const uint local_pixel = (uint)get_global_id(0);
  if (local_pixel >= params.pixel_count) return;
  PixelAccumulator acc = pixel_accumulator_new();
  for (uint s = 0; s < params.samples_per_pass; ++s) {
    const uint j = s * params.pixel_count + local_pixel;
    pixel_accumulator_add(&acc, v3(results[4 * j], results[4 * j + 1], results[4 * j + 2]),
                          as_uint(results[4 * j + 3]));
  }
  film_write_pass(&pass[local_pixel], &acc);
}
