/* megakernel.cl: the megakernel execution form.
 *
 * One work-item per path (job) of the launch: job j is sample sample_begin + j / pixel_count of
 * pixel pixel_begin + j % pixel_count. It runs the stages of path.cl in a loop, one segment per
 * iteration, until the path ends, and leaves its result for film_sum_jobs (film.cl). The loop's
 * data-dependent length keeps PoCL from vectorising this form across work-items (an unrolled,
 * masked loop measured no faster); GPUs run it as is. Reads: the sphere buffer and
 * GpuRenderParams, and the light buffer (nee). Writes: results. */
#include "types.h"
#include "path.cl"
#include "film.cl"

__kernel void render_paths(__global const GpuSphere* spheres, __global const GpuLight* lights,
                           const GpuRenderParams params, __global float* results) {
  const uint job = (uint)get_global_id(0);
  if (job >= params.pixel_count * params.samples_per_pass) return;
  PathState path = path_begin(&params, params.pixel_begin + job % params.pixel_count,
                              params.sample_begin + job / params.pixel_count);
  while (path.alive) {
    path_shade(&path, path_intersect(&path, spheres, &params), spheres, lights, &params);
  }
  job_result_store(results, job, path.radiance, path.segments);
}
