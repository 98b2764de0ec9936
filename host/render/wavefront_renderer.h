// The split wavefront execution form (kernels/wavefront.cl): a pool of path slots in
// structure-of-arrays buffers, one kernel per stage over the densely packed active paths,
// shading storing the survivors densely into a second set of buffers, and freed slots refilled with the pass's
// next samples until every sample of the pass is done.
#pragma once

#include <map>
#include <vector>

#include "cl/cl_context.h"
#include "kernels/kernel_options.h"
#include "render/renderer.h"
#include "scene/device_scene.h"

namespace clpt {

class WavefrontRenderer : public Renderer {
 public:
  // paths_in_flight 0: chosen from the device (default_paths_in_flight).
  WavefrontRenderer(DeviceContext& ctx, const DeviceScene& scene, const KernelFeatures& features,
                    uint32_t paths_in_flight = 0, size_t local_size = 0);

  std::vector<GpuPixelPass> render_pass(const GpuRenderParams& params, const GpuSampleSlot* slots = nullptr) override;
  // One result slot (result_bytes_per_job, render/limits.h) per sample of the pass: bounded to launch_buffer_budget()
  // = min(kMaxLaunchBufferBytes, the device's max allocation / 2), but at least one sample.
  uint32_t max_samples_per_pass(uint32_t pixel_count) const override;
  std::vector<StageTime> stage_times() const override;

  // GPUs: 16384 paths per compute unit, within [65536, 4M], enough to fill the lanes many times
  // over. CPUs: 32768 per compute unit: each launch has a fixed cost on PoCL, and fewer, larger
  // launches beat keeping the state in cache (measured on PoCL, 2 cores, 640x480 x 16 spp:
  // 1.74 M paths/s at 8192 per compute unit, 1.95 M at 32768, no better at 65536; README "Speed").
  static uint32_t default_paths_in_flight(const DeviceInfo& device);
  static constexpr size_t kDefaultLocalSize = 64;
  // wf_shade ranks a work-group's survivors in local memory sized for this many (wavefront.cl).
  static constexpr size_t kMaxLocalSize = 1024;

 private:
  // Binds a set of state buffers to consecutive arguments from first_index; returns the next index.
  cl_uint bind(Kernel& kernel, cl_uint first_index, const std::vector<Buffer>& buffers);
  // Keeps a launch's event until collect_times(), after the next blocking call, adds it up.
  void record(const char* label, EventHandle event);
  void collect_times();
  void generate(const GpuRenderParams& params, uint32_t job_begin, uint32_t slot_begin, uint32_t count);
  uint32_t intersect_and_shade(const GpuRenderParams& params, uint32_t active);

  DeviceContext& ctx_;
  uint32_t paths_;
  size_t local_size_;
  ProgramHandle program_;
  Kernel generate_, intersect_, shade_, film_;
  SceneBufferSet scene_;
  std::vector<Buffer> state_, next_state_;  // one per CLPT_PATH_STATE_FIELDS entry, twice
  std::vector<Buffer> scratch_;               // one per CLPT_PATH_SCRATCH_FIELDS entry
  Buffer survivors_, results_, pass_;
  const Buffer* sample_slots_ = nullptr;  // this pass's slots (Renderer::upload_slots)
  std::map<std::string, StageTime> times_;
  std::vector<std::pair<const char*, EventHandle>> pending_;
};

}  // namespace clpt
