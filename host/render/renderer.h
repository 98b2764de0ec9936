// What a pass needs from an execution form. MegakernelRenderer and WavefrontRenderer implement
// it from the same stage functions (kernels/path.cl); RenderSession drives either.
#pragma once

#include <string>
#include <vector>

#include "cl/cl_context.h"
#include "kernels/kernel_options.h"
#include "kernels/types.h"
#include "scene/device_scene.h"

namespace clpt {

enum class ExecutionForm { Megakernel, Wavefront };
const char* execution_form_name(ExecutionForm form);

// Time spent in one labelled kernel, from OpenCL profiling events (seconds, summed).
struct StageTime {
  std::string label;
  double seconds = 0;
  uint64_t launches = 0;
};

class Renderer {
 public:
  virtual ~Renderer() = default;

  // Traces params.samples_per_pass samples from params.sample_begin for the pixels
  // [params.pixel_begin, +pixel_count) and returns their pass statistics (blocking). An adaptive
  // launch (params.slotted) traces them for each of its pixel_count `slots` instead (a pixel and
  // its first sample each; kernels/film.cl) and returns one entry per slot.
  virtual std::vector<GpuPixelPass> render_pass(const GpuRenderParams& params,
                                                const GpuSampleSlot* slots = nullptr) = 0;

  // Largest samples_per_pass this renderer accepts for `pixel_count` pixels (memory bound).
  virtual uint32_t max_samples_per_pass(uint32_t pixel_count) const = 0;

  // The first-hit layers' sums of the last render_pass (kernels/film_aov.cl): CLPT_AOV_CHANNELS
  // floats (kernels/aov_channels.h) per entry of its result, in the same order; empty when the
  // kernel has no layers (KernelFeatures::aovs).
  const std::vector<float>& aov_sums() const { return aov_sums_; }

  // Per-kernel device time so far (empty when not measured).
  virtual std::vector<StageTime> stage_times() const { return {}; }

  double build_seconds() const { return build_seconds_; }

  // The scene's buffers (also for tools that run a kernel of their own on a scene, e.g.
  // tools/traversal_trace.h), in the kernels' argument order (kernels/bvh.cl, SceneBuffers). None is
  // ever empty (OpenCL has no zero-sized buffers): an unused one holds a zeroed placeholder entry;
  // GpuRenderParams' counts say how many entries count.
  struct SceneBufferSet {
    Buffer spheres, lights, nodes, triangles, triangle_shading, environment, texturing;
  };
  static SceneBufferSet upload_scene(DeviceContext& ctx, const DeviceScene& scene);
  // Sets the seven scene buffers as arguments first, first + 1, ...; returns the next index.
  static cl_uint bind_scene(Kernel& kernel, cl_uint first, const SceneBufferSet& scene);

 protected:
  // Builds the program of `entry_file` (e.g. "megakernel.cl") specialised for `features`,
  // recording the build time (driver and clpt caches included). The options are the plan's
  // (render_plan.h), which reports them.
  ProgramHandle build(DeviceContext& ctx, const std::string& entry_file, const KernelFeatures& features);
  // The entry point `name` of the program `build` made for `ctx`, carrying the lanes PoCL's
  // vectoriser compiles it with: those of the features it was built with, which its build options
  // carry too (cl/pocl_vectoriser.h).
  Kernel entry_point(const DeviceContext& ctx, const ProgramHandle& program, const char* name) const;

  // The launch's slot buffer: `slots` (params.pixel_count of them) written to the device for an
  // adaptive launch; for a uniform one a placeholder entry the kernels never read.
  const Buffer& upload_slots(DeviceContext& ctx, const GpuRenderParams& params, const GpuSampleSlot* slots);

  // With the first-hit layers (features.aovs): film_sum_aovs of `program`, for sum_aovs. Called
  // once, after the build; without the layers nothing.
  void prepare_aovs(const DeviceContext& ctx, const ProgramHandle& program, const KernelFeatures& features);
  // After a pass's jobs have left their results: their layers' sums into aov_sums() (blocking).
  // Nothing without the layers.
  void sum_aovs(DeviceContext& ctx, const GpuRenderParams& params, const Buffer& results, size_t local_size);

  double build_seconds_ = 0;
  bool aovs_ = false;  // the kernel records the first-hit layers (set by prepare_aovs)

 private:
  Kernel film_aovs_;
  Buffer aov_pass_;
  std::vector<float> aov_sums_;
  uint32_t cpu_vector_lanes_ = 0;  // of the features of the last build
  bool pocl_slp_ = true;           // likewise: SLP off for the triangle loop's kernels (cl/pocl_vectoriser.h)
  Buffer slots_;
};

}  // namespace clpt
