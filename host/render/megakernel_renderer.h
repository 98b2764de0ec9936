// The megakernel execution form (kernels/megakernel.cl): one work-item per path, looping over
// its segments (alone, or in lockstep with its work-group on CPUs), then film_sum_jobs sums each
// pixel's samples. Passes are split into launches over
// pixel ranges (device_pool.h, work_queue.h) so that no launch trips a display watchdog.
#pragma once

#include <vector>

#include "cl/cl_context.h"
#include "kernels/kernel_options.h"
#include "render/renderer.h"
#include "scene/device_scene.h"

namespace clpt {

class MegakernelRenderer : public Renderer {
 public:
  // Builds the program for `features` and uploads the scene. The loop is the plan's
  // (render_plan.h): lockstep in work-groups of features.lockstep_group when that is non-zero,
  // per path otherwise. local_size: the per-path loop's work-group size (0: the driver chooses);
  // the lockstep loop always launches work-groups of features.lockstep_group.
  MegakernelRenderer(DeviceContext& ctx, const DeviceScene& scene, const KernelFeatures& features,
                     size_t local_size = 0);

  // Traces params.samples_per_pass samples, starting at params.sample_begin, for the pixels
  // [params.pixel_begin, +pixel_count) and returns their pass statistics (blocking).
  std::vector<GpuPixelPass> render_pass(const GpuRenderParams& params, const GpuSampleSlot* slots = nullptr) override;

  // One result slot (result_bytes_per_job, render/limits.h) per sample of a launch, within
  // launch_buffer_budget.
  uint32_t max_samples_per_pass(uint32_t pixel_count) const override;


  // Work-group size of launches over part of the image when the constructor got 0.
  static constexpr size_t kPartialLaunchLocalSize = 64;

 private:
  DeviceContext& ctx_;
  ProgramHandle program_;
  Kernel kernel_, film_;
  SceneBufferSet scene_;
  Buffer results_, pass_;
  size_t local_size_ = 0;
  uint32_t lockstep_group_ = 0;  // the lockstep loop's work-group size, 0: per-path loop
};

}  // namespace clpt
