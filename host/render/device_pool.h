// The devices of one render (--device 0,1 / all), each with its own context and renderer, sharing
// every pass. Within a pass the devices pull pixel ranges from one queue (work_queue.h), each
// range sized from that device's own measured throughput, so fast devices take more; the film
// adds each range under a lock. A device whose build or launch throws clpt::Error is retired: its
// unfinished range goes back to the queue for the others. One device is the N = 1 case of the
// same code, with the launches of a single-device render.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "render/fault_injection.h"
#include "render/film.h"
#include "render/render_plan.h"
#include "render/renderer.h"
#include "render/work_queue.h"
#include "scene/device_scene.h"

namespace clpt {

class KernelCache;

// One device's part in a render (RenderReport::devices).
struct DeviceShare {
  std::string device;             // label, "device 'NAME' (PLATFORM)"
  ExecutionForm form = ExecutionForm::Megakernel;
  bool built = false;             // its context and renderer were set up (a failed set-up: false)
  double build_seconds = 0;       // the program's build (clBuildProgram, or a binary from a cache)
  double first_launch_seconds = 0;  // warm_up's launch: what the driver compiles at a first launch
  uint64_t paths = 0;             // samples it traced in this run
  uint64_t segments = 0;          // ray segments of those samples
  uint64_t launches = 0;          // pixel ranges it traced
  double busy_seconds = 0;        // wall time inside its launches (results read back included)
  std::string failure;            // empty: it worked to the end; else the error that retired it
};

class DevicePool {
 public:
  // Builds a context and renderer on every device of the plan, in parallel (one thread per
  // device), as the plan says. A device whose set-up throws clpt::Error (no fp64 for double, too
  // little memory, a failed build) is retired with a notice. Throws when none is left: the
  // device's own error when there was one device, else an Error naming every device's failure.
  // `scene` must outlive the constructor.
  DevicePool(const RenderPlan& plan, const DeviceScene& scene, FaultPlan faults = FaultPlan::from_environment());
  ~DevicePool();
  DevicePool(const DevicePool&) = delete;
  DevicePool& operator=(const DevicePool&) = delete;

  // Launches every working device's kernels once, in parallel, over the first few pixels of
  // `params`'s image with one sample each, and drops the results (sample indices are fixed by
  // pixel and number, so no pass draws differently for it). What a driver compiles at a kernel's
  // first launch rather than in clBuildProgram (PoCL: the work-group functions, seconds on a cold
  // cache) is done here, timed as each device's first_launch_seconds, not in the first pass, where
  // it would count as tracing and size the next launches from a rate it does not have. A device
  // whose launch throws clpt::Error is retired, as in a pass. Blocking; returns the wall time.
  // Throws as run_pass does when every device has failed.
  double warm_up(const GpuRenderParams& params);

  // Traces the pass `params` (samples_per_pass from sample_begin, over the whole image) into
  // `film`; every working device pulls ranges until the pass is done. Blocking. Throws as the
  // constructor does when every device has failed before the pass was complete (the film then
  // holds part of the pass and must not be used); rethrows any other exception of a device.
  // An adaptive pass (params.slotted) passes its `slots`, params.pixel_count of them, which the
  // devices take in ranges as they take pixels of a uniform pass.
  void run_pass(const GpuRenderParams& params, Film& film, const std::vector<GpuSampleSlot>* slots = nullptr);

  // Receives each traced range of a pass: its pixel results, their first-hit layers' sums
  // (Renderer::aov_sums; empty without the layers) and its first pixel. Called under the pool's
  // lock, one range at a time.
  using PassSink = std::function<void(const std::vector<GpuPixelPass>& result, const std::vector<float>& aovs,
                                      uint32_t pixel_begin)>;
  // As run_pass, over the pixels `pixels` of the pass only (an MPI rank's part, rank_pass.h), each
  // traced range handed to `sink` instead of a film.
  void run_pass_part(const GpuRenderParams& params, PixelRange pixels, const PassSink& sink,
                     const std::vector<GpuSampleSlot>* slots = nullptr);
  // True once every device has been retired (run_pass and run_pass_part then throw).
  bool every_device_failed() const;

  // The largest samples per pass every working device accepts for `pixel_count` pixels.
  uint32_t max_samples_per_pass(uint32_t pixel_count) const;

  // Messages for the user about devices retired since the last call ("device 1 (...) failed:
  // ...; its work goes to the other devices").
  std::vector<std::string> take_notices();

  // Every device's part so far, in plan order (failed ones too).
  std::vector<DeviceShare> shares() const;
  // Device time per stage of the passes (warm_up's launch left out), summed over the devices
  // (wavefront; empty for the megakernel).
  std::vector<StageTime> stage_times() const;
  // clpt's kernel binary cache as used by the first device that built (null when off or none).
  std::shared_ptr<KernelCache> kernel_cache() const;

 private:
  struct Member;
  struct PassState;

  // A range taken from the pass's queue, with its number among the member's launches (1 = its
  // first; what CLPT_INJECT_FAULT counts). count 0: none.
  struct Taken {
    PixelRange range;
    uint64_t launch = 0;
  };

  void build(Member& member, const DevicePlan& plan, const DeviceScene& scene);
  void warm_up(Member& member, const GpuRenderParams& params);
  // `first`: the range run_pass handed the member before its thread started.
  void work(Member& member, const GpuRenderParams& params, const GpuSampleSlot* slots, const PassSink& sink,
            PassState& pass, Taken first);
  // Takes member's next range from a non-empty queue; called under mutex_.
  Taken take_range(Member& member, PassState& pass, uint32_t samples);
  // Pixels of member's next range; called under mutex_.
  uint32_t range_pixels(Member& member, uint32_t remaining, uint32_t samples) const;
  // Marks member failed with the exception being handled; called under mutex_.
  void retire(Member& member, const std::string& what, std::exception_ptr error);
  [[noreturn]] void throw_every_device_failed() const;
  size_t working_count() const;

  std::vector<std::unique_ptr<Member>> members_;  // in --device list order
  FaultPlan faults_;
  mutable std::mutex mutex_;             // members' counters, the pass queue, the film, notices
  std::condition_variable changed_;      // a range was given back or finished
  std::vector<std::string> notices_;
  std::exception_ptr fatal_;             // an exception that is not a device failure
};

}  // namespace clpt
