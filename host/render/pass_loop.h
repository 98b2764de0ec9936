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
#include "render/render_session.h"
#include "render/renderer.h"

namespace clpt {

// How the megakernel's launches are sized.
struct LaunchSizing {
  double target_s = 0.075;           // wall time per launch; <= 0: one launch per pass
  uint32_t first_pixels = 4096;      // pixels of the first launch, before any measurement
  uint32_t max_pixels = UINT32_MAX;  // memory bound: the pass buffer holds 32 B per pixel
};

// A launch may cover at most this many times the pixels of the one before: small launches
// under-use the device and so under-estimate its throughput; growth by steps stays safe.
constexpr uint32_t kMaxLaunchGrowth = 4;

// Pixels for the next launch of a pass. Pure. remaining: pixels of the pass not yet launched;
// samples: samples per pixel of the pass; pixel_samples_per_s: measured throughput of the last
// launch (0: none yet, use first_pixels); previous: pixels of the last launch (0: none). The
// result is in [1, remaining] (0 when remaining is 0); a tail of under a quarter of a launch is
// folded into it, so passes do not end in a sliver.
uint32_t next_launch_pixels(const LaunchSizing& sizing, uint32_t remaining, uint32_t samples,
                            double pixel_samples_per_s, uint32_t previous);

struct PassLoopOptions {
  uint64_t target_spp = 0;       // 0: until the time limit (at most kMaxSpp)
  double time_limit_s = 0;       // 0: none
  double pass_target_s = 0.5;    // wall time per pass, from the measured rate
  uint32_t granularity = 1;      // samples per pass are a multiple of this (sampler period)
  // Set asynchronously (a signal handler); checked between passes: the running pass finishes.
  const std::atomic<bool>* interrupt = nullptr;
  // Called between passes, at most every checkpoint_every_s seconds (none when empty).
  std::function<void(const Film&)> checkpoint;
  // Called once, after the first pass (none when empty); see RenderRequest::after_first_pass.
  std::function<void()> after_first_pass;
  double checkpoint_every_s = 60;
  bool show_progress = false;
};

class DevicePool;

// Adds passes to `film` (which may already hold samples: a resumed render continues at
// sample index film.samples_per_pixel()), each traced by the devices of `pool` (one or several).
// `params` describes the whole image. Fills passes and interrupted (true only when the loop
// stopped early for an interrupt) in `report`; prints the pool's notices of failed devices on
// stderr. Blocking; throws what the pool throws.
void run_passes(DevicePool& pool, const GpuRenderParams& params, Film& film,
                const PassLoopOptions& options, RenderReport& report);

}  // namespace clpt
