/* film.cl: per-pixel statistics of one pass.
 *
 * The paths of a launch leave their results per job; film_sum_jobs then gives each pixel to one
 * work-item, which sums its samples in blocks of 16 in `real` (float, or double under the double
 * preset; a pass holds at most 4096 samples) and writes, not adds, its GpuPixelPass. The host adds
 * passes in double. Samples with a NaN or Inf channel are dropped here (bit test, survives fast
 * maths) and show up as valid_samples < samples. */
#ifndef CLPT_FILM_CL
#define CLPT_FILM_CL

#include "types.h"
#include "maths.cl"

/* Sums of a set of samples of one pixel: radiance and squared radiance per channel, in `real`. */
typedef struct RadianceSums {
  Vec3 sum;
  Vec3 sum_sq;
} RadianceSums;

CLPT_INLINE RadianceSums radiance_sums_new(void) {
  RadianceSums acc;
  acc.sum = v3_splat(0.0f);
  acc.sum_sq = v3_splat(0.0f);
  return acc;
}

/* acc += value (one sample, already finite). */
CLPT_INLINE void radiance_sums_add(RadianceSums* acc, Vec3 value) {
  acc->sum = v3_add(acc->sum, value);
  acc->sum_sq = v3_add(acc->sum_sq, v3_mul(value, value));
}

/* acc += other (sums of disjoint sample sets). */
CLPT_INLINE void radiance_sums_merge(RadianceSums* acc, const RadianceSums* other) {
  acc->sum = v3_add(acc->sum, other->sum);
  acc->sum_sq = v3_add(acc->sum_sq, other->sum_sq);
}

/* A pass's statistics of one pixel: the sums, and the counts, which are integers and exact. */
typedef struct PixelAccumulator {
  RadianceSums sums;
  uint valid_samples;
  uint segments;
} PixelAccumulator;

CLPT_INLINE void film_write_pass(__global GpuPixelPass* out, const PixelAccumulator* acc) {
  out->sum[0] = (float)acc->sums.sum.x;
  out->sum[1] = (float)acc->sums.sum.y;
  out->sum[2] = (float)acc->sums.sum.z;
  out->valid_samples = (float)acc->valid_samples; /* exact: a pass has far fewer than 2^24 samples */
  out->sum_sq[0] = (float)acc->sums.sum_sq.x;
  out->sum_sq[1] = (float)acc->sums.sum_sq.y;
  out->sum_sq[2] = (float)acc->sums.sum_sq.z;
  out->segments = acc->segments;
}

/* Job results, as both execution forms leave them: job j of a launch is sample j / pixel_count of
 * slot j % pixel_count (job_pixel, job_sample below). They are planar, n = pixel_count * samples_per_pass jobs per plane:
 * results[j], results[n + j], results[2 n + j] hold its radiance, results[3 n + j] the bits of its
 * segment count. Planar, not four floats per job: four adjacent stores let the compiler pair a
 * path's colour channels into 2-wide vectors (SLP), which stops PoCL's vectoriser across
 * work-items; on GPUs, planes make the stores coalesce. */
CLPT_INLINE uint job_count(const GpuRenderParams* params) { return params->pixel_count * params->samples_per_pass; }

/* The pixel and the sample index job j traces. A launch has pixel_count slots of samples_per_pass
 * samples each; job j is sample j / pixel_count of slot j % pixel_count. A uniform launch's slot s
 * is pixel pixel_begin + s from sample sample_begin; an adaptive launch's (params->slotted) is
 * slots[s], a pixel and its first sample, so one pixel may have several slots or none
 * (render/adaptive_sampling.h). film_sum_jobs sums per slot; the host adds each slot to its pixel. */
CLPT_INLINE uint job_pass_sample(const GpuRenderParams* params, uint job) { return clpt_udiv(job, params->pixel_count); }
CLPT_INLINE uint job_slot(const GpuRenderParams* params, uint job) {
  return job - job_pass_sample(params, job) * params->pixel_count;
}

CLPT_INLINE uint job_pixel(const GpuRenderParams* params, __global const GpuSampleSlot* slots, uint job) {
  const uint slot = job_slot(params, job);
  return params->slotted ? slots[slot].pixel : params->pixel_begin + slot;
}

CLPT_INLINE uint job_sample(const GpuRenderParams* params, __global const GpuSampleSlot* slots, uint job) {
  const uint first = params->slotted ? slots[job_slot(params, job)].sample_begin : params->sample_begin;
  return first + job_pass_sample(params, job);
}

CLPT_INLINE void job_result_store(__global float* results, uint job, uint jobs, Vec3 radiance, uint segments) {
  results[job] = (float)radiance.x;
  results[jobs + job] = (float)radiance.y;
  results[2u * jobs + job] = (float)radiance.z;
  results[3u * jobs + job] = as_float(segments);
}

/* Blocked summation in three levels of CLPT_FILM_BLOCK = 16: the samples of a pass are summed
 * sixteen at a time, sixteen such sums into a sum of 256, and those into the pass's total. Each
 * sample passes through at most 3 x 15 additions instead of up to 4095 one after another, so the
 * relative rounding error of a pass of 4096 is bounded by about 45 ulps instead of 4095: a pass
 * of 4096 samples of 0.7, summed sequentially in float, came out 4e-5 low, the same way in every
 * pass (so the double accumulation over passes kept the bias); blocked, 1.7e-7 low (pairwise
 * summation, which needed a 13-level array, 0; the accuracy the films need is 1e-6, the 1e7-spp
 * test in test_extremes_stat.cpp). 16^3 = 4096 = kMaxSamplesPerPass (render_session.h); a larger
 * pass would only lengthen the outermost, sequential, sum.
 * Three accumulators in registers, indexed by nothing: the pairwise sum's carry array, indexed by
 * the trailing one bits of the sample number, lived in private memory (632 bytes of scratch per
 * work-item on gfx906, a 624-byte local depot in PTX), slow memory on every GPU.
 * Under -cl-fast-relaxed-math (fast preset) the compiler may reassociate: it may reorder the
 * additions within one block, which leaves the bound unchanged (any order of 16 terms has the
 * same one), but a block's partial sum is a value carried by its own loop and added once to its
 * parent's: folding it into one flat running sum would be a change of the loop structure, which
 * reassociation of an expression does not license in practice. A compensated (Kahan) sum relies
 * on (t - s) - x being non-zero in float, which reassociation simplifies to exactly 0: it would
 * silently become the sequential sum under the fast preset. */
#define CLPT_FILM_BLOCK 16u

/* Sample s of this launch's pixel `local_pixel` (its jobs: film.cl header), NaN/Inf dropped. */
CLPT_INLINE void film_add_sample(PixelAccumulator* total, RadianceSums* block, __global const float* results,
                                 uint jobs, uint j) {
  const Vec3 radiance = v3(results[j], results[jobs + j], results[2u * jobs + j]);
  const bool valid = v3_all_finite(radiance);
  radiance_sums_add(block, v3_select(valid, radiance, v3_splat(0.0f)));
  total->valid_samples += valid ? 1u : 0u;
  total->segments += as_uint(results[3u * jobs + j]);
}

/* One work-item per slot of the launch (a pixel, or an adaptive pass's slot): its samples summed in
 * sample order, so the sums do not depend on which form traced them or in what order. */
__kernel void film_sum_jobs(const GpuRenderParams params, __global const float* results,
                            __global GpuPixelPass* pass) {
  const uint local_pixel = (uint)get_global_id(0);
  if (local_pixel >= params.pixel_count) return;
  const uint jobs = job_count(&params);
  const uint n = params.samples_per_pass;
  PixelAccumulator total;
  total.sums = radiance_sums_new();
  total.valid_samples = 0u;
  total.segments = 0u;
  uint s = 0u;
  while (s < n) {
    RadianceSums of_256 = radiance_sums_new();
    for (uint b = 0u; b < CLPT_FILM_BLOCK && s < n; ++b) {
      RadianceSums of_16 = radiance_sums_new();
      for (uint c = 0u; c < CLPT_FILM_BLOCK && s < n; ++c, ++s)
        film_add_sample(&total, &of_16, results, jobs, s * params.pixel_count + local_pixel);
      radiance_sums_merge(&of_256, &of_16);
    }
    radiance_sums_merge(&total.sums, &of_256);
  }
  film_write_pass(&pass[local_pixel], &total);
}

#endif
