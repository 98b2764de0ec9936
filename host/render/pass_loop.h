// The pass loop of a render: passes of whole sample counts over the image until the sample count,
// the time budget or the target error is reached (what each pass is: pass_schedule.h), or an
// interrupt is requested. Each pass is traced by a PassTracer: the devices of this process's
// DevicePool, in launches over pixel ranges (on the megakernel each launch is sized from the
// measured throughput to take about a target time, so no launch runs into a display GPU's
// watchdog, docs/numerics.md "Watchdogs"), or those of every rank of an MPI job (rank_pass.h).
// The next pass is decided in one place, plan_next_pass, by the coordinator alone (the process,
// or rank 0), and every rank runs the decision it is sent.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "render/film.h"
#include "render/pass_schedule.h"

namespace clpt {

struct PassLoopOptions {
  PassRequest request;           // stopping rule (spp, time, target error) and pass sizing
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
  // Wall time of the passes themselves, summed: each PassTracer::trace, i.e. the launches and the
  // waits for them (and in an MPI job the ranks' parts reaching rank 0), as `clpt bench` times a
  // pass; not the work between passes (error estimates, progress, checkpoints).
  double trace_seconds = 0;
  bool interrupted = false;  // stopped early: the interrupt was set before the target was reached
  StopReason stop = StopReason::None;  // what ended it (None when interrupted)
  ErrorEstimate estimate;              // of the final film
};

// What the next pass is, as the coordinator decided it and every rank runs it: the schedule's
// answer (pass_schedule.h), or an interrupt. Plain bytes, broadcast as they are (rank_pass.cpp).
struct PassDecision {
  NextPass next;             // next.stop != None: the sample count, time or target error is reached
  bool interrupted = false;  // an interrupt (of any rank) came before the target was reached
  bool stop() const { return interrupted || next.stop != StopReason::None; }
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
  // Traces `pass` (samples_per_pass from sample_begin, over the whole image; or, adaptive, over
  // its `slots`, which only the coordinator need pass); on the coordinator its results are in
  // `film` when it returns, every pixel (slot) added once. Throws Error(DeviceError) when every
  // device (of every rank) has failed.
  virtual void trace(const GpuRenderParams& pass, Film& film, const std::vector<GpuSampleSlot>* slots) = 0;
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
  void trace(const GpuRenderParams& pass, Film& film, const std::vector<GpuSampleSlot>* slots) override;
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

}  // namespace clpt
