// One render from a loaded scene to a finished film: pick the device, specialise and build the
// kernel, run passes until the sample count or time budget is reached, accumulate in double.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "kernels/kernel_options.h"
#include "render/film.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace clpt {

class KernelCache;

struct RenderRequest {
  Scene scene;               // settings already merged with command-line overrides
  std::string device = "";   // --device value ("" = best; "all" or a comma list: several devices)
  double time_limit_s = 0;   // --time; 0 = none (then settings.spp decides)
  bool spp_given = true;     // false when only --time bounds the render
  bool show_progress = false;
  Precision precision = Precision::Robust;  // --precision
  std::optional<Intersection> intersection;  // --intersection; unset: the preset's
  bool generic_kernel = false;  // compile every feature, not only what the scene needs
  size_t local_size = 0;        // work-group size; 0 lets the driver choose
  std::optional<ExecutionForm> form;  // unset: the device's default (default_form_for)
  MegakernelLoop megakernel_loop = MegakernelLoop::Auto;  // --megakernel-loop
  SceneLoops scene_loops = SceneLoops::Auto;               // --scene-loops
  uint32_t paths_in_flight = 0;       // wavefront only; 0 chooses from the device
  bool use_kernel_cache = true;       // clpt's kernel binary cache (--no-cache turns it off)
  // Megakernel launches are sized to take about this long (watchdogs); <= 0: one per pass.
  double launch_target_s = 0.075;
  // Polled between passes; when it becomes true the running pass finishes and the render stops.
  const std::atomic<bool>* interrupt = nullptr;
  // A checkpoint to continue from (render/checkpoint.h): sampling resumes at its spp.
  std::optional<Film> resume;
  // Called once, after the first pass (none when empty): host work to overlap with the rest of
  // the render, such as loading the image writer. Not before: OpenCL drivers load their kernels
  // (PoCL: a shared object per kernel) at the first launch, and a dlopen on another thread would
  // hold the dynamic loader's lock against them.
  std::function<void()> after_first_pass;
  // Called between passes at most every checkpoint_every_s seconds (none when empty).
  std::function<void(const Film&)> checkpoint;
  double checkpoint_every_s = 60;
};

// One device's part in a render (RenderReport::devices).
struct DeviceShare {
  std::string device;             // label, "device 'NAME' (PLATFORM)"
  ExecutionForm form = ExecutionForm::Megakernel;
  double build_seconds = 0;
  uint64_t paths = 0;             // samples it traced in this run
  uint64_t segments = 0;          // ray segments of those samples
  uint64_t launches = 0;          // pixel ranges it traced
  double busy_seconds = 0;        // wall time inside its launches (results read back included)
  std::string failure;            // empty: it worked to the end; else the error that retired it
};

struct RenderReport {
  std::string device;          // label of the device used (several: joined with " + ")
  std::string build_options;
  double build_seconds = 0;    // program build, including any driver cache hit
  double render_seconds = 0;   // passes only
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
  std::vector<DeviceShare> devices;  // every device of --device, in its order (failed ones too)
};

struct DeviceInfo;
class DeviceContext;
struct DeviceScene;
struct KernelFeatures;

// Kernel parameters of a whole-image pass for this scene (sample_begin/samples_per_pass unset).
GpuRenderParams make_params(const Scene& scene, const DeviceScene& device_scene);

// The renderer of an execution form, with its program built for `features`.
std::unique_ptr<Renderer> make_renderer(ExecutionForm form, DeviceContext& ctx,
                                        const DeviceScene& scene, const KernelFeatures& features,
                                        uint32_t paths_in_flight, size_t local_size);

// Throws Error(Device) naming the device when it cannot run `precision` (double without fp64).
void check_precision_supported(Precision precision, const DeviceInfo& device);

// The execution form used when none is asked for on this device (README: "Execution forms").
ExecutionForm default_form_for(const DeviceInfo& device);

// Blocking. Throws clpt::Error on device or build failure.
Film run_render(const RenderRequest& request, RenderReport& report);

// Samples per pass: the first pass is one sampler period, later passes aim at target_s seconds
// from the measured rate, capped by what is left and by kMaxSamplesPerPass.
uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity);

constexpr uint32_t kMaxSamplesPerPass = 4096;  // keeps each pass's float sums exact enough
// kernels/film.cl sums a pass in three levels of blocks of CLPT_FILM_BLOCK = 16 samples, whose
// error bound (about 45 ulps) holds up to 16^3 samples; a larger pass would still be summed, with
// a longer sequential outermost level and a looser bound.
static_assert(kMaxSamplesPerPass <= 16 * 16 * 16, "film.cl's blocked sum has three levels of 16");

}  // namespace clpt
