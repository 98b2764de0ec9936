/* film_aov.cl: the first-hit layers' results and per-pixel sums of one pass (CLPT_AOVS, decided in
 * kernel_options.cpp; aov.cl records them along a path; docs/aovs.md).
 *
 * A job's layers follow film.cl's four planes in the same results buffer: results[(4 + c) n + j]
 * holds channel c (aov_channels.h) of job j, n = pixel_count * samples_per_pass jobs per plane,
 * planar for the reasons film.cl gives. The host sizes the buffer for 4 + CLPT_AOV_CHANNELS
 * planes when the kernel has the layers (render/limits.h, result_bytes_per_job).
 * film_sum_aovs gives each slot of the launch (a pixel, or an adaptive pass's slot) to one
 * work-item, which sums its samples' channels in sample order in film_sum_jobs' blocks of 16,
 * and writes CLPT_AOV_CHANNELS floats for the slot: the same samples as the radiance's sums, so
 * the host's mean (sums added in double, render/film.h) is over the beauty's samples. A
 * non-finite value (none is expected: the values are clamped or unit or a hit distance) counts
 * as 0. Both drivers include this file only with CLPT_AOVS. */
#ifndef CLPT_FILM_AOV_CL
#define CLPT_FILM_AOV_CL

#include "types.h"
#include "maths.cl"
#include "path.cl"
#include "film.cl"
#include "aov_channels.h"

#define CLPT_AOV_FIRST_PLANE 4u /* after film.cl's radiance (3) and segment count (1) */

/* The layers of finished path p, as job `job` of `jobs`. */
CLPT_INLINE void job_aov_store(__global float* results, uint job, uint jobs, const PathState* p) {
  __global float* planes = results + CLPT_AOV_FIRST_PLANE * jobs + job;
  planes[(CLPT_AOV_ALBEDO + 0u) * jobs] = (float)p->aov_albedo.x;
  planes[(CLPT_AOV_ALBEDO + 1u) * jobs] = (float)p->aov_albedo.y;
  planes[(CLPT_AOV_ALBEDO + 2u) * jobs] = (float)p->aov_albedo.z;
  planes[(CLPT_AOV_NORMAL + 0u) * jobs] = (float)p->aov_normal.x;
  planes[(CLPT_AOV_NORMAL + 1u) * jobs] = (float)p->aov_normal.y;
  planes[(CLPT_AOV_NORMAL + 2u) * jobs] = (float)p->aov_normal.z;
  planes[CLPT_AOV_DEPTH * jobs] = (float)p->aov_depth;
}

/* One work-item per slot of the launch: each channel's sum over the slot's samples. */
__kernel void film_sum_aovs(const GpuRenderParams params, __global const float* results, __global float* sums) {
  const uint slot = (uint)get_global_id(0);
  if (slot >= params.pixel_count) return;
  const uint jobs = job_count(&params);
  const uint n = params.samples_per_pass;
  for (uint c = 0u; c < CLPT_AOV_CHANNELS; ++c) {
    __global const float* plane = results + (CLPT_AOV_FIRST_PLANE + c) * jobs;
    real total = (real)0;
    uint s = 0u;
    while (s < n) {
      real of_256 = (real)0;
      for (uint b = 0u; b < CLPT_FILM_BLOCK && s < n; ++b) {
        real of_16 = (real)0;
        for (uint k = 0u; k < CLPT_FILM_BLOCK && s < n; ++k, ++s) {
          const float v = plane[s * params.pixel_count + slot];
          of_16 += is_finite_bits(v) ? (real)v : (real)0;
        }
        of_256 += of_16;
      }
      total += of_256;
    }
    sums[slot * CLPT_AOV_CHANNELS + c] = (float)total;
  }
}

#endif
