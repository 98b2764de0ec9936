// What the next pass of a render is: its samples, its half-film, or that the render stops (the
// sample count, the time budget or the target error is reached). Decided in ONE function,
// plan_next_pass, from the film, the request and the loop's measurements, so that a coordinator
// (the pass loop; a rank 0 that broadcasts it) computes it once for every device or rank.
//
// With a target error the stopping rule is evaluated only at check points, totals of samples per
// pixel on a fixed ladder (check_ladder_at_or_above) at which both half-films hold equal samples.
// Sample indices: half 0 draws samples 0, 1, 2, ... of each pixel and half 1 samples 2^31,
// 2^31 + 1, ... (kernels/types.h, CLPT_SAMPLE_STREAM_BIT), so the halves are independent for every
// sampler, and a render of S samples ends with halves of half0_end(S) and S minus that samples
// whatever its pass sizes were: the same seed and S give the same image on any devices, split and
// resumed anyhow.
//
// Which check points are visited depends only on the estimates at earlier check points, and the
// estimates depend only on the samples, which the counter-based RNG fixes by (seed, pixel,
// sample): the sample count at which a render stops does not depend on the device split, the
// pass sizes or the timing. Pass sizes between check points follow the measured rate (about
// pass_target_s per pass) and change only the float rounding of the pass sums.
#pragma once

#include <cstdint>

#include "render/error_estimate.h"
#include "render/film.h"

namespace clpt {

// The stopping rule and pass sizing a render asks for.
struct PassRequest {
  uint64_t target_spp = 0;    // 0: no sample limit (kMaxSpp)
  double time_limit_s = 0;    // 0: none
  double target_error = 0;    // relative RMSE (error_estimate.h) at which to stop; 0: none
  uint32_t granularity = 1;   // samples per pass are a multiple of this (sampler period)
  // Sobol samplers: a render of S samples gives half 0 the smallest power of two at or above
  // S / 2 and half 1 the rest (half0_end), not two equal halves, because their points are
  // stratified in power-of-two blocks: 6 spp as 4 + 2 had 18% less squared error than as 3 + 3
  // (docs/sampler.md, "Half-films"). The render plan sets it only without a target error, whose
  // estimate wants equal halves.
  bool power_of_two_halves = false;
  double pass_target_s = 0.5; // wall time per pass, from the measured rate
  bool adaptive = false;      // adaptive sampling (adaptive_sampling.h): rounds, and passes sized by the image alone
};

// Adaptive mode: a pass holds about this many samples whatever the devices' rate (a uniform pass
// rounds it up to whole samples per pixel and the sampler's granularity), so that the passes, and
// the film's float sums, do not depend on the device split (adaptive_sampling.h). About 0.13 s on
// the 2-core test machine; an adaptive pass's slot results wait for the film in host memory
// (32 bytes a slot, at most 32 MiB).
constexpr uint64_t kAdaptivePassSamples = uint64_t(1) << 20;

// What the pass loop has measured so far.
struct PassMeasurements {
  int passes = 0;                       // passes run in this process
  double elapsed_s = 0;                 // since the loop started
  double samples_per_pixel_per_s = 0;   // of the last pass; 0 before the first
  uint32_t max_samples_per_pass = 0;    // the devices' limit for the image (0: kMaxSamplesPerPass)
};

// The schedule's memory between calls: the next check point (0: not chosen yet; a resumed render
// starts at the first ladder point at or above its samples).
struct PassScheduleState {
  uint64_t next_check_spp = 0;
};

enum class StopReason { None, SampleCount, TimeLimit, TargetError };

struct NextPass {
  StopReason stop = StopReason::None;  // None: run the pass below
  // Index of the pass's first sample: the half's samples so far, from 0 for half 0 and from
  // 2^CLPT_SAMPLE_STREAM_BIT for half 1 (kernels/types.h: an independent Sobol randomisation).
  uint32_t sample_begin = 0;
  uint32_t samples = 0;                // samples per pixel (per slot, adaptive) of the pass
  int half = 0;                        // the half-film it goes to (the smaller unless full; 1 when adaptive)
  // An adaptive pass: slots [slot_begin, slot_begin + slot_count) of its round's table
  // (adaptive_sampling.h), `samples` (the granularity) each; sample_begin is then unused.
  bool adaptive = false;
  uint64_t slot_begin = 0;
  uint32_t slot_count = 0;
  ErrorEstimate estimate;              // of the film before the pass
  // Target error: the total samples per pixel the estimate predicts the target needs (error
  // falling as 1/sqrt(spp)); 0 when unknown.
  uint64_t predicted_spp = 0;
};

// Where half 0 ends in a render of `spp` samples per pixel without a target error: granularity g
// times ceil(spp / 2g), or with power_of_two_halves the smallest power of two at or above that
// (rounded up to g, at most spp). Half 1 ends at spp minus it.
uint64_t half0_end(uint64_t spp, uint32_t granularity, bool power_of_two_halves);

// The sample count at which `request` stops: its target_spp, or kMaxSpp when it has none.
uint64_t stop_spp(const PassRequest& request);

// Deterministic: the same film, request, measurements and state give the same answer. Updates
// `state` at check points. `estimate` must be estimate_error(film): a caller that has it already
// (the pass loop, which shows it on the progress line) passes it in; the short form computes it.
NextPass plan_next_pass(const Film& film, const ErrorEstimate& estimate, const PassRequest& request,
                        const PassMeasurements& measured, PassScheduleState& state);
NextPass plan_next_pass(const Film& film, const PassRequest& request, const PassMeasurements& measured,
                        PassScheduleState& state);

// The first check point at or above `spp` for a sampler of this granularity. The ladder starts
// at 2 x max(8, granularity) (each half at least 8 samples before any stop) and grows by about
// 1/8 a step, in even multiples of the granularity. After a check that fails, the next check is
// the ladder point at or above 0.95 x the predicted samples, at most 1.5 x the samples so far.
uint64_t check_ladder_at_or_above(uint64_t spp, uint32_t granularity);

// Samples per pass from the rate alone: the first pass is one sampler period, later passes aim at
// target_s seconds from the measured rate, capped by what is left and by kMaxSamplesPerPass.
uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity);

// The samples per pixel at which `estimate` (taken at `spp`) predicts the target is reached, the
// upper estimate falling as 1/sqrt(spp); 0 when the estimate is invalid.
uint64_t predicted_spp_for(const ErrorEstimate& estimate, uint64_t spp, double target_error);

const char* stop_reason_name(StopReason reason);

}  // namespace clpt
