// The resolved plan of one render: every decision a render makes, taken once, in one place, from
// the scene, the request and the chosen devices, before any device work. `clpt render`, `bench`,
// `tradeoff`, `verify` and the tests all run from it (render_session.h runs one), and
// `clpt render --explain` prints it. Per device: execution form and megakernel loop, the kernel's
// features and build options (kernels/kernel_options.h decides them), work-group and path-pool
// sizes, how launches are sized, and the device memory the render needs. For the render: image,
// stopping rule (spp, time, target error) and sampler granularity.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "render/limits.h"
#include "render/render_request.h"
#include "render/renderer.h"
#include "render/work_queue.h"
#include "scene/device_scene.h"

namespace clpt {

struct DevicePlan {
  size_t position = 0;  // in the --device list (CLPT_INJECT_FAULT's device number)
  DeviceInfo device;
  ExecutionForm form = ExecutionForm::Megakernel;
  std::string form_reason;     // why this form: "--form" or the rule's reason (render/form_rule.h)
  KernelFeatures features;     // resolved: lockstep_group set for the lockstep loop, else 0
  std::string entry_file;      // the program's kernel file: megakernel.cl or wavefront.cl
  std::string build_options;   // kernel_build_options(features)
  // Work-group size of the main kernel as launched; 0: the driver's choice (the per-path
  // megakernel's whole-image launches; its partial launches use kPartialLaunchLocalSize).
  size_t local_size = 0;
  uint32_t paths_in_flight = 0;  // wavefront path slots; 0 for the megakernel
  bool kernel_cache = false;     // clpt's binary cache: asked for and the driver keeps none of its own
  LaunchSizing sizing;           // how this device's ranges of a pass are sized
  MemoryEstimate memory;         // device memory the render needs there
};

struct RenderPlan {
  int width = 0, height = 0;
  uint32_t image_pixels = 0;
  uint64_t target_spp = 0;       // 0: only the time limit stops the render
  double time_limit_s = 0;       // 0: none
  double target_error = 0;       // stop at this estimated relative RMSE (render/error_estimate.h); 0: none
  uint32_t sampler_granularity = 1;  // samples per pass are a multiple of this (grid: 16)
  bool power_of_two_halves = false;  // Sobol samplers' half-film split (render/pass_schedule.h)
  bool adaptive = false;             // adaptive sampling (render/adaptive_sampling.h)
  Precision precision = Precision::Robust;
  bool use_kernel_cache = true;
  std::vector<DevicePlan> devices;  // in --device list order
  // Some device's kernel tests the meshes of large triangles in its loop beside the hierarchy
  // (KernelFeatures::loop_beside_hierarchy): the device scene then keeps them in a subtree of
  // their own (make_device_scene). Else one hierarchy over every triangle, as the other kernels
  // traverse best.
  bool loop_meshes_apart = false;
  std::string textures;  // one line per texture image: size, storage, device bytes (device_textures.h); "" for none
};

// The plan for `request` on `devices` (already selected from the --device value). Pure: no
// device is touched; checks that need the device (fp64, memory) happen when the pool builds.
RenderPlan plan_render(const RenderRequest& request, const std::vector<DeviceInfo>& devices);

// Every decision of the plan, a few lines per device, for --explain. `vector_widths`, when not
// empty, holds one measured description per device of the plan (tools/vector_width.h, measured by
// the caller: this stays pure), printed in that device's kernel specialisation block.
std::string explain_plan(const RenderPlan& plan, const std::vector<std::string>& vector_widths = {});

// Throws Error(Device) naming the device when it cannot run `precision` (double without fp64).
void check_precision_supported(Precision precision, const DeviceInfo& device);

// Kernel parameters of a whole-image pass for this scene (sample_begin/samples_per_pass unset).
GpuRenderParams make_params(const Scene& scene, const DeviceScene& device_scene);

}  // namespace clpt
