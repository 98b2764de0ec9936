#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

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
  cpu_vector_lanes_ = features.cpu_vector_lanes;
  pocl_slp_ = !features.triangles_in_loop();
  return program;
}

Kernel Renderer::entry_point(const DeviceContext& ctx, const ProgramHandle& program, const char* name) const {
  return Kernel(program.get(), name, ctx.where(), cpu_vector_lanes_, pocl_slp_);
}

namespace {
// A read-only buffer holding `entries`, or one zeroed entry when there are none.
template <typename T>
Buffer upload_entries(DeviceContext& ctx, const std::vector<T>& entries, const char* label) {
  const T placeholder{};
  const T* data = entries.empty() ? &placeholder : entries.data();
  const size_t bytes = std::max<size_t>(entries.size(), 1) * sizeof(T);
  Buffer buffer(ctx, bytes, CL_MEM_READ_ONLY, label);
  ctx.write(buffer, data, bytes);
  return buffer;
}
}  // namespace

Renderer::SceneBufferSet Renderer::upload_scene(DeviceContext& ctx, const DeviceScene& scene) {
  SceneBufferSet set;
  set.spheres = upload_entries(ctx, scene.spheres, "spheres");
  set.lights = upload_entries(ctx, scene.lights, "lights");
  set.nodes = upload_entries(ctx, scene.bvh.nodes, "hierarchy nodes");
  set.triangles = upload_entries(ctx, scene.triangles, "triangles");
  set.triangle_shading = upload_entries(ctx, scene.triangle_shading, "triangle shading");
  return set;
}

const Buffer& Renderer::upload_slots(DeviceContext& ctx, const GpuRenderParams& params, const GpuSampleSlot* slots) {
  const size_t entries = params.slotted ? params.pixel_count : 1;
  if (slots_.bytes() < entries * sizeof(GpuSampleSlot))
    slots_ = Buffer(ctx, entries * sizeof(GpuSampleSlot), CL_MEM_READ_ONLY, "sample slots");
  if (params.slotted) {
    if (!slots) throw std::logic_error("Renderer: an adaptive launch without its slots");
    ctx.write(slots_, slots, entries * sizeof(GpuSampleSlot));
  }
  return slots_;
}

cl_uint Renderer::bind_scene(Kernel& kernel, cl_uint first, const SceneBufferSet& scene) {
  for (const Buffer* b : {&scene.spheres, &scene.lights, &scene.nodes, &scene.triangles, &scene.triangle_shading})
    kernel.set_arg(first++, *b);
  return first;
}

}  // namespace clpt
