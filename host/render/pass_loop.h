// The pass loop of a render: passes of whole sample counts over the image until the sample count,
// the time budget or the target error is reached (what each pass is: pass_schedule.h), or an
// interrupt is requested. Each pass is traced by the devices
// of a DevicePool in launches over pixel ranges; on the megakernel each launch is sized from the
// measured throughput to take about a target time, so no launch runs into a display GPU's
// watchdog (docs/numerics.md, "Watchdogs").
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>

#include "render/film.h"
#include "render/pass_schedule.h"

namespace clpt {

struct PassLoopOptions {
  PassRequest request;           // stopping rule (spp, time, target error) and pass sizing
  // Set asynchronously (a signal handler); checked between passes: the running pass finishes.
  const std::atomic<bool>* interrupt = nullptr;
  // Called between passes, at most every checkpoint_every_s seconds (none when empty).
  std::function<void(const Film&)> checkpoint;
  // Called once, after the first pass (none when empty); see RenderRequest::after_first_pass.
  std::function<void()> after_first_pass;
  double checkpoint_every_s = 60;
  bool show_progress = false;
};

// What the loop did.
struct PassLoopResult {
  int passes = 0;
  bool interrupted = false;  // stopped early: the interrupt was set before the target was reached
  StopReason stop = StopReason::None;  // what ended it (None when interrupted)
  ErrorEstimate estimate;              // of the final film
};

class DevicePool;

// Adds passes to `film` (which may already hold samples: a resumed render continues at
// sample index film.samples_per_pixel()), each traced by the devices of `pool` (one or several).
// `params` describes the whole image. Prints the pool's notices of failed devices on stderr.
// Blocking; throws what the pool throws.
PassLoopResult run_passes(DevicePool& pool, const GpuRenderParams& params, Film& film,
                          const PassLoopOptions& options);

}  // namespace clpt
