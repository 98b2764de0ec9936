// The pass loop of a render: passes of whole sample counts over the image until the sample count
// or the time budget is reached, or an interrupt is requested. Each pass is traced by a
// PassTracer: the devices of this process's DevicePool, in launches over pixel ranges (on the
// megakernel each launch is sized from the measured throughput to take about a target time, so no
// launch runs into a display GPU's watchdog, docs/numerics.md "Watchdogs"), or those of every rank
// of an MPI job (rank_pass.h). The next pass is decided in one place, decide_next_pass, by the
// coordinator alone (the process, or rank 0), and every rank runs the decision it is sent.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

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

// What the next pass is, as the coordinator decided it and every rank runs it. The one place of a
// render where passes are decided: a stopping rule (a target error, issue 16) or a per-pixel
// sample allocation belongs here, sent with the decision (rank_pass.cpp encodes it).
struct PassDecision {
  bool stop = false;         // no more passes
  bool interrupted = false;  // stop: because of an interrupt before the target was reached
  uint32_t sample_begin = 0; // the pass's first sample index (every pixel)
  uint32_t samples = 0;      // samples per pixel of the pass
};

// How the passes are traced: by this process's devices (DevicePoolTracer), or by every rank of an
// MPI job (RankPassTracer, rank_pass.h).
class PassTracer {
 public:
  virtual ~PassTracer() = default;
  // Whether this process decides the passes and holds the film (a single process; rank 0).
  virtual bool coordinator() const = 0;
  // Gives every rank the coordinator's `decision` (a single process: unchanged).
  virtual void share(PassDecision& decision) = 0;
  // Traces `pass` (samples_per_pass from sample_begin, over the whole image); on the coordinator
  // its results are in `film` when it returns, every pixel added once. Throws Error(DeviceError)
  // when every device (of every rank) has failed.
  virtual void trace(const GpuRenderParams& pass, Film& film) = 0;
  // The largest samples per pass every working device accepts for `pixel_count` pixels.
  virtual uint32_t max_samples_per_pass(uint32_t pixel_count) const = 0;
  // Whether another process of the job has been interrupted (SIGINT/SIGTERM reached it).
  virtual bool others_interrupted() const { return false; }
  // Messages about devices or ranks retired since the last call.
  virtual std::vector<std::string> take_notices() = 0;
};

class DevicePool;

// The passes traced by this process's devices alone: DevicePool::run_pass.
class DevicePoolTracer final : public PassTracer {
 public:
  explicit DevicePoolTracer(DevicePool& pool) : pool_(pool) {}
  bool coordinator() const override { return true; }
  void share(PassDecision&) override {}
  void trace(const GpuRenderParams& pass, Film& film) override;
  uint32_t max_samples_per_pass(uint32_t pixel_count) const override;
  std::vector<std::string> take_notices() override;

 private:
  DevicePool& pool_;
};

// Adds passes to `film` (which may already hold samples: a resumed render continues at
// sample index film.samples_per_pixel()), each traced by `tracer`. `params` describes the whole
// image. Prints the tracer's notices of failed devices on stderr. On a rank other than the
// coordinator, `film` stays empty, and progress and checkpoints are the coordinator's. Blocking;
// throws what the tracer throws.
PassLoopResult run_passes(PassTracer& tracer, const GpuRenderParams& params, Film& film,
                          const PassLoopOptions& options);

// Samples per pass: the first pass is one sampler period, later passes aim at target_s seconds
// from the measured rate, capped by what is left and by kMaxSamplesPerPass (limits.h).
uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity);

}  // namespace clpt
