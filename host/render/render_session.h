// One render from a loaded scene to a finished film, narrated in run_render: select the devices,
// resolve the plan (render_plan.h: every decision, once), convert the scene for the kernels,
// build on every device (device_pool.h), run passes until the sample count or time budget is
// reached (pass_loop.h), and report what happened. Accumulation is in double (film.h).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "render/device_pool.h"
#include "render/film.h"
#include "render/limits.h"
#include "render/pass_loop.h"
#include "render/rank_pass.h"
#include "render/render_plan.h"
#include "render/render_request.h"
#include "render/renderer.h"

namespace clpt {

class KernelCache;

// What a render did: the plan's first device's form and options, and every device's part.
// Its times (seconds, wall clock) do not overlap, so their sum is at most the render's wall time;
// what they leave out is the devices' contexts and scene uploads, and the work between passes.
struct RenderReport {
  std::string device;          // label of the device used (several: joined with " + ")
  std::string build_options;   // of the first device that built
  double discovery_seconds = 0;  // the OpenCL platforms and devices listed, selected, the plan made
  double convert_seconds = 0;  // the scene converted for the kernels, its hierarchy built (device_scene.h)
  double build_seconds = 0;    // program build, including any driver cache hit (the slowest device)
  double first_launch_seconds = 0;  // DevicePool::warm_up: what drivers compile at a first launch
  // The passes alone: their launches and the waits for them (PassLoopResult::trace_seconds), the
  // time `clpt bench` measures; every rate of the summary is over this time.
  double pass_seconds = 0;
  // The pass loop: the passes and the work between them (error estimates, progress, checkpoints);
  // what --time limits.
  double render_seconds = 0;
  int passes = 0;
  uint64_t spp = 0;
  uint64_t paths = 0;
  uint64_t segments = 0;
  uint64_t dropped = 0;        // samples with NaN/Inf radiance, excluded from the film
  ExecutionForm form = ExecutionForm::Megakernel;
  Precision precision = Precision::Robust;
  uint32_t paths_in_flight = 0;  // wavefront only
  std::vector<StageTime> stage_times;
  std::shared_ptr<KernelCache> kernel_cache;  // the one used (null when off); hits() > 0: loaded
  uint64_t launches = 0;     // kernel launches of the passes (megakernel: pixel-range launches)
  bool interrupted = false;  // stopped early: `interrupt` was set before the target was reached
  StopReason stop = StopReason::None;  // what ended the passes (None when interrupted)
  ErrorEstimate estimate;              // clpt's estimate of the final film's error (error_estimate.h)
  std::vector<DeviceShare> devices;  // every device of --device, in its order (failed ones too)
  // An MPI job: every rank's part, at rank 0 (empty on the other ranks and in a single process).
  // The other fields are the job's at rank 0 (paths, spp, seconds) and this rank's devices.
  std::vector<RankShare> ranks;
};

// Blocking. Throws clpt::Error on device or build failure (JobError on every rank of an MPI job
// when the ranks disagree or every rank failed). On ranks other than 0 the returned film is empty.
Film run_render(const RenderRequest& request, RenderReport& report);

}  // namespace clpt
