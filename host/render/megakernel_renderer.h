// The megakernel execution form: one kernel launch per pass, one work-item per pixel looping
// over that pixel's samples and each path's bounces (kernels/megakernel.cl).
#pragma once

#include <vector>

#include "cl/cl_context.h"
#include "kernels/kernel_options.h"
#include "scene/device_scene.h"

namespace clpt {

class MegakernelRenderer {
 public:
  // Builds the program for `features` and uploads the scene. local_size 0 lets the driver choose.
  MegakernelRenderer(DeviceContext& ctx, const DeviceScene& scene, const KernelFeatures& features,
                     size_t local_size = 0);

  // Traces params.samples_per_pass samples, starting at params.sample_begin, for the pixels
  // [params.pixel_begin, +pixel_count) and returns their pass statistics (blocking).
  std::vector<GpuPixelPass> render_pass(const GpuRenderParams& params);

  double build_seconds() const { return build_seconds_; }
  const std::string& build_options() const { return build_options_; }

 private:
  DeviceContext& ctx_;
  std::string build_options_;
  double build_seconds_ = 0;
  ProgramHandle program_;
  Kernel kernel_;
  Buffer spheres_;
  Buffer pass_;
  size_t local_size_;
};

}  // namespace clpt
