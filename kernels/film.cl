/* film.cl: per-pixel statistics of one pass.
 *
 * The paths of a launch leave their results per job; film_sum_jobs then gives each pixel to one
 * work-item, which sums its samples pairwise in `real` (float, or double under the double preset;
 * a pass holds at most 4096 samples) and writes, not adds, its GpuPixelPass. The host adds passes in double. Samples with a NaN or Inf channel are
 * dropped here (bit test, survives fast maths) and show up as valid_samples < samples. */
#ifndef CLPT_FILM_CL
#define CLPT_FILM_CL

#include "types.h"
#include "maths.cl"

typedef struct PixelAccumulator {
  Vec3 sum;
  Vec3 sum_sq;
  real valid_samples;
  uint segments;
} PixelAccumulator;

CLPT_INLINE PixelAccumulator pixel_accumulator_new(void) {
  PixelAccumulator acc;
  acc.sum = v3_splat(0.0f);
  acc.sum_sq = v3_splat(0.0f);
  acc.valid_samples = (real)0;
  acc.segments = 0u;
  return acc;
}

CLPT_INLINE void pixel_accumulator_add(PixelAccumulator* acc, Vec3 radiance, uint segments) {
  acc->segments += segments;
  const bool valid = v3_all_finite(radiance);
  const Vec3 value = v3_select(valid, radiance, v3_splat(0.0f));
  acc->sum = v3_add(acc->sum, value);
  acc->sum_sq = v3_add(acc->sum_sq, v3_mul(value, value));
  acc->valid_samples += valid ? (real)1 : (real)0;
}

/* acc += other (sums of disjoint sample sets). */
CLPT_INLINE void pixel_accumulator_merge(PixelAccumulator* acc, const PixelAccumulator* other) {
  acc->sum = v3_add(acc->sum, other->sum);
  acc->sum_sq = v3_add(acc->sum_sq, other->sum_sq);
  acc->valid_samples += other->valid_samples;
  acc->segments += other->segments;
}

CLPT_INLINE void film_write_pass(__global GpuPixelPass* out, const PixelAccumulator* acc) {
  out->sum[0] = (float)acc->sum.x;
  out->sum[1] = (float)acc->sum.y;
  out->sum[2] = (float)acc->sum.z;
  out->valid_samples = (float)acc->valid_samples;
  out->sum_sq[0] = (float)acc->sum_sq.x;
  out->sum_sq[1] = (float)acc->sum_sq.y;
  out->sum_sq[2] = (float)acc->sum_sq.z;
  out->segments = acc->segments;
}

/* Job results, as both execution forms leave them: job j of a launch is sample j / pixel_count of
 * pixel j % pixel_count. They are planar, n = pixel_count * samples_per_pass jobs per plane:
 * results[j], results[n + j], results[2 n + j] hold its radiance, results[3 n + j] the bits of its
 * segment count. Planar, not four floats per job: four adjacent stores let the compiler pair a
 * path's colour channels into 2-wide vectors (SLP), which stops PoCL's vectoriser across
 * work-items; on GPUs, planes make the stores coalesce. */
CLPT_INLINE uint job_count(const GpuRenderParams* params) { return params->pixel_count * params->samples_per_pass; }

CLPT_INLINE void job_result_store(__global float* results, uint job, uint jobs, Vec3 radiance, uint segments) {
  results[job] = (float)radiance.x;
  results[jobs + job] = (float)radiance.y;
  results[2u * jobs + job] = (float)radiance.z;
  results[3u * jobs + job] = as_float(segments);
}

/* Pairwise (cascade) summation: partial sums of 1, 2, 4, ... samples, merged like the carries of a
 * binary counter, so that each sample passes through about log2(n) additions instead of n. A pass
 * of 4096 equal samples of 0.7 summed one after another in float came out 4e-5 low, the same way
 * in every pass (so the double accumulation over passes kept the bias); summed pairwise it is
 * exact. 13 levels cover kMaxSamplesPerPass = 4096. */
#define CLPT_PAIRWISE_LEVELS 13

/* One work-item per pixel of the launch: its samples summed in sample order, so the sums do not
 * depend on which form traced them or in what order. */
__kernel void film_sum_jobs(const GpuRenderParams params, __global const float* results,
                            __global GpuPixelPass* pass) {
  const uint local_pixel = (uint)get_global_id(0);
  if (local_pixel >= params.pixel_count) return;
  PixelAccumulator level[CLPT_PAIRWISE_LEVELS];
  const uint jobs = job_count(&params);
  for (uint s = 0; s < params.samples_per_pass; ++s) {
    const uint j = s * params.pixel_count + local_pixel;
    PixelAccumulator carry = pixel_accumulator_new();
    pixel_accumulator_add(&carry, v3(results[j], results[jobs + j], results[2u * jobs + j]),
                          as_uint(results[3u * jobs + j]));
    /* Sample s completes the partial sums of the levels where s has trailing one bits. */
    uint l = 0u;
    for (; (s >> l) & 1u; ++l) pixel_accumulator_merge(&carry, &level[l]);
    level[l] = carry;
  }
  PixelAccumulator total = pixel_accumulator_new();
  for (uint l = 0u; l < CLPT_PAIRWISE_LEVELS; ++l)
    if ((params.samples_per_pass >> l) & 1u) pixel_accumulator_merge(&total, &level[l]);
  film_write_pass(&pass[local_pixel], &total);
}

#endif
