// What a user asks of one render: the scene (with the command line's overrides merged in), the
// devices, the kernel and execution choices, the stopping rule and the host-side callbacks.
// Data only: render_plan.h turns it into every decision a render makes, render_session.h runs it.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "kernels/kernel_options.h"
#include "render/aov_set.h"
#include "render/fault_injection.h"
#include "render/film.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace clpt {

struct RenderPlan;
class RankGroup;

struct RenderRequest {
  Scene scene;               // settings already merged with command-line overrides
  std::string device = "";   // --device value ("" = best; "all" or a comma list: several devices)
  double time_limit_s = 0;   // --time; 0 = none (then settings.spp decides)
  double target_error = 0;   // --target-error: relative RMSE to stop at (render/error_estimate.h); 0 = none
  bool spp_given = true;     // false when only --time or --target-error bound the render
  bool adaptive = false;     // --adaptive: adaptive sampling (render/adaptive_sampling.h)
  bool show_progress = false;
  Precision precision = Precision::Robust;  // --precision
  std::optional<Intersection> intersection;  // --intersection; unset: the preset's
  bool generic_kernel = false;  // compile every feature, not only what the scene needs
  size_t local_size = 0;        // work-group size; 0 lets the driver choose
  std::optional<ExecutionForm> form;  // unset: the rule's (render/form_rule.h, default_form_for)
  MegakernelLoop megakernel_loop = MegakernelLoop::Auto;  // --megakernel-loop
  SceneLoops scene_loops = SceneLoops::Auto;               // --scene-loops
  CpuVectorBits cpu_vector_bits = CpuVectorBits::Auto;     // --cpu-vector-bits
  SphereReads sphere_reads = SphereReads::Auto;            // --sphere-reads
  uint32_t paths_in_flight = 0;       // wavefront only; 0 chooses from the device
  bool use_kernel_cache = true;       // clpt's kernel binary cache (--no-cache turns it off)
  // --aovs: the first-hit layers to record (any: CLPT_AOVS compiled, the film accumulates all
  // three; the EXR holds those asked for). Neither a checkpoint nor a resumed film carries them.
  AovSet aovs;
  // Megakernel launches are sized to take about this long (watchdogs); <= 0: one per pass.
  double launch_target_s = 0.075;
  // Polled between passes; when it becomes true the running pass finishes and the render stops.
  const std::atomic<bool>* interrupt = nullptr;
  // A checkpoint to continue from (render/checkpoint.h): sampling resumes at its spp.
  std::optional<Film> resume;
  // Called between passes at most every checkpoint_every_s seconds (none when empty).
  std::function<void(const Film&)> checkpoint;
  double checkpoint_every_s = 60;
  // Called once with the resolved plan, after device selection and before any device work (none
  // when empty): `clpt render --explain` prints it.
  std::function<void(const RenderPlan&)> on_plan;
  // Injected faults (render/fault_injection.h); unset: CLPT_INJECT_FAULT from the environment.
  // `clpt verify` sets it: none for its reference renders, the tested device's own faults for
  // the device's.
  std::optional<FaultPlan> faults;
  // The processes sharing this render (render/rank_group.h); null or a group of one: this
  // process alone. Every rank of a larger group calls run_render with the same request, except
  // that only rank 0's `resume`, `checkpoint` and `on_plan` are used.
  RankGroup* ranks = nullptr;
};

}  // namespace clpt
