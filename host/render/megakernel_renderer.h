// The megakernel execution form: one kernel launch per pass, one work-item per pixel looping
// over that pixel's samples and each path's bounces (kernels/megakernel.cl).
#pragma once

#include <vector>

#include "cl/cl_context.h"
#include "kernels/kernel_options.h"
#include "render/renderer.h"
#include "scene/device_scene.h"

namespace clpt {

class MegakernelRenderer : public Renderer {
 public:
  // Builds the program for `features` and uploads the scene. local_size 0 lets the driver choose.
  MegakernelRenderer(DeviceContext& ctx, const DeviceScene& scene, const KernelFeatures& features,
                     size_t local_size = 0);

  // Traces params.samples_per_pass samples, starting at params.sample_begin, for the pixels
  // [params.pixel_begin, +pixel_count) and returns their pass statistics (blocking).
  std::vector<GpuPixelPass> render_pass(const GpuRenderParams& params) override;

  // The pass buffer holds only per-pixel sums: any sample count fits.
  uint32_t max_samples_per_pass(uint32_t) const override { return UINT32_MAX; }

  // Work-group size of launches over part of the image when the constructor got 0.
  static constexpr size_t kPartialLaunchLocalSize = 64;

 private:
  DeviceContext& ctx_;
  ProgramHandle program_;
  Kernel kernel_;
  Buffer spheres_;
  Buffer pass_;
  size_t local_size_;
};

}  // namespace clpt
