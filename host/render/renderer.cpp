#include "render/renderer.h"

#include <chrono>

#include "kernels/kernel_source.h"
#include "util/clock.h"

namespace clpt {

const char* execution_form_name(ExecutionForm form) {
  return form == ExecutionForm::Wavefront ? "wavefront" : "megakernel";
}

ProgramHandle Renderer::build(DeviceContext& ctx, const std::string& entry_file,
                              const KernelFeatures& features) {
  const auto start = Clock::now();
  ProgramHandle program =
      ctx.build_program(assemble_kernel_source(entry_file), kernel_build_options(features), entry_file);
  build_seconds_ = seconds_since(start);
  return program;
}

void Renderer::upload_scene(DeviceContext& ctx, const DeviceScene& scene, Buffer& spheres, Buffer& lights) {
  const size_t sphere_bytes = scene.spheres.size() * sizeof(GpuSphere);
  spheres = Buffer(ctx, sphere_bytes, CL_MEM_READ_ONLY, "spheres");
  ctx.write(spheres, scene.spheres.data(), sphere_bytes);
  std::vector<GpuLight> entries = scene.lights;
  if (entries.empty()) entries.push_back(GpuLight{});
  lights = Buffer(ctx, entries.size() * sizeof(GpuLight), CL_MEM_READ_ONLY, "lights");
  ctx.write(lights, entries.data(), entries.size() * sizeof(GpuLight));
}

}  // namespace clpt
