#include "render/renderer.h"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#include "kernels/aov_channels.h"
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

void Renderer::prepare_aovs(const DeviceContext& ctx, const ProgramHandle& program, const KernelFeatures& features) {
  aovs_ = features.aovs;
  if (aovs_) film_aovs_ = entry_point(ctx, program, "film_sum_aovs");
}

void Renderer::sum_aovs(DeviceContext& ctx, const GpuRenderParams& params, const Buffer& results, size_t local_size) {
  if (!aovs_) return;
  const size_t floats = size_t(params.pixel_count) * CLPT_AOV_CHANNELS;
  if (aov_pass_.bytes() < floats * sizeof(float))
    aov_pass_ = Buffer(ctx, floats * sizeof(float), CL_MEM_WRITE_ONLY, "first-hit layer sums");
  film_aovs_.set_arg(0, params);
  film_aovs_.set_arg(1, results);
  film_aovs_.set_arg(2, aov_pass_);
  ctx.launch(film_aovs_, params.pixel_count, local_size, "film_sum_aovs");
  aov_sums_.resize(floats);
  ctx.read(aov_pass_, aov_sums_.data(), floats * sizeof(float));
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
  set.nodes = upload_entries(ctx, hierarchy_device_data(scene), "hierarchy nodes and leaf triangles");
  set.triangles = upload_entries(ctx, scene.triangles, "triangles");
  set.triangle_shading = upload_entries(ctx, scene.triangle_shading, "triangle shading");
  set.environment = upload_entries(ctx, scene.environment, "environment");
  // The texturing bytes (device_textures.h), or a zeroed header: no texturing (the generic kernel
  // reads it; texture.cl, triangle_texture_material).
  std::vector<GpuTexturing> placeholder;
  set.texturing = scene.texturing.empty() ? upload_entries(ctx, placeholder, "texturing")
                                          : upload_entries(ctx, scene.texturing, "texturing");
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
  for (const Buffer* b : {&scene.spheres, &scene.lights, &scene.nodes, &scene.triangles, &scene.triangle_shading,
                           &scene.environment, &scene.texturing})
    kernel.set_arg(first++, *b);
  return first;
}

}  // namespace clpt
