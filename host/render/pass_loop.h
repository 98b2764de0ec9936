// The pass loop of a render: passes of whole sample counts over the image until the sample count
// or the time budget is reached, or an interrupt is requested. Each pass is traced by the devices
// of a DevicePool in launches over pixel ranges; on the megakernel each launch is sized from the
// measured throughput to take about a target time, so no launch runs into a display GPU's
// watchdog (docs/numerics.md, "Watchdogs").
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "render/film.h"

namespace clpt {

struct PassLoopOptions {
  uint64_t target_spp = 0;       // 0: until the time limit (at most kMaxSpp)
  double time_limit_s = 0;       // 0: none
  double pass_target_s = 0.5;    // wall time per pass, from the measured rate
  uint32_t granularity = 1;      // samples per pass are a multiple of this (sampler period)
  // Set asynchronously (a signal handler); checked between passes: the running pass finishes.
  const std::atomic<bool>* interrupt = nullptr;
  // Called between passes, at most every checkpoint_every_s seconds (none when empty).
  std::function<void(const Film&)> checkpoint;
  double checkpoint_every_s = 60;
  bool show_progress = false;
};

// What the loop did.
struct PassLoopResult {
  int passes = 0;
  bool interrupted = false;  // stopped early: the interrupt was set before the target was reached
};

class DevicePool;

// Adds passes to `film` (which may already hold samples: a resumed render continues at
// sample index film.samples_per_pixel()), each traced by the devices of `pool` (one or several).
// `params` describes the whole image. Prints the pool's notices of failed devices on stderr.
// Blocking; throws what the pool throws.
PassLoopResult run_passes(DevicePool& pool, const GpuRenderParams& params, Film& film,
                          const PassLoopOptions& options);

// Samples per pass: the first pass is one sampler period, later passes aim at target_s seconds
// from the measured rate, capped by what is left and by kMaxSamplesPerPass (limits.h).
uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity);

}  // namespace clpt
