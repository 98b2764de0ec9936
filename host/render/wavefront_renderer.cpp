#include "render/wavefront_renderer.h"

#include <algorithm>

#include "kernels/path_state.h"
#include "render/limits.h"
#include "util/error.h"

namespace clpt {
uint32_t WavefrontRenderer::default_paths_in_flight(const DeviceInfo& device) {
  const uint32_t paths = device.is_cpu ? std::clamp<uint32_t>(device.compute_units * 32768u, 32768u, 1u << 21)
                                       : std::clamp<uint32_t>(device.compute_units * 16384u, 65536u, 4u << 20);
  // The stage kernels' launches span the active paths: under the width at which the driver would
  // compile them again (cl_device.h), as the first launch is.
  const uint32_t limit = device.uniform_launch_limit();
  return limit > 0 ? std::min(paths, limit) : paths;
}

WavefrontRenderer::WavefrontRenderer(DeviceContext& ctx, const DeviceScene& scene,
                                     const KernelFeatures& features, uint32_t paths_in_flight,
                                     size_t local_size)
    : ctx_(ctx),
      paths_(paths_in_flight ? paths_in_flight : default_paths_in_flight(ctx.device())),
      // A fixed work-group size: the number of active paths changes every launch, and a driver left
      // to choose would pick (and PoCL would compile a kernel variant for) a new size each time.
      local_size_(local_size ? local_size : kDefaultLocalSize) {
  if (local_size_ > kMaxLocalSize)
    throw Error(ExitCode::Usage, "--local-size " + std::to_string(local_size_) + ": the wavefront's work-groups hold at most " +
                                     std::to_string(kMaxLocalSize) + " work-items");
  program_ = build(ctx, "wavefront.cl", features);  // scene loops as planned (render_plan.h)
  generate_ = entry_point(ctx, program_, "wf_generate");
  intersect_ = entry_point(ctx, program_, "wf_intersect");
  shade_ = entry_point(ctx, program_, "wf_shade");
  film_ = entry_point(ctx, program_, "film_sum_jobs");
  prepare_aovs(ctx, program_, features);

  scene_ = upload_scene(ctx, scene);
  // `real` state fields are float, or double under the double preset.
  const size_t real_bytes = features.precision == Precision::Double ? 8 : 4;
#define CLPT_REAL_BYTES real_bytes
#define CLPT_HOST_AOVS aovs_  // the first-hit layers' fields only in a kernel that has them
  // One work-group of slots beyond the pool: wf_shade's work-items past the active count load their
  // own (unused) slot rather than a clamped one (wavefront.cl).
#define CLPT_ALLOCATE(type, name, bytes, doc)                                              \
  set->emplace_back(ctx, (size_t(paths_) + local_size_) * (bytes), CL_MEM_READ_WRITE, "path state " #name);
  for (std::vector<Buffer>* set : {&state_, &next_state_}) {
    CLPT_PATH_STATE_FIELDS(CLPT_ALLOCATE)
  }
  {
    std::vector<Buffer>* set = &scratch_;
    CLPT_PATH_SCRATCH_FIELDS(CLPT_ALLOCATE)
  }
#undef CLPT_ALLOCATE
#undef CLPT_HOST_AOVS
#undef CLPT_REAL_BYTES
  survivors_ = Buffer(ctx, sizeof(cl_uint), CL_MEM_READ_WRITE, "survivor count");
}

cl_uint WavefrontRenderer::bind(Kernel& kernel, cl_uint first_index, const std::vector<Buffer>& buffers) {
  for (const Buffer& b : buffers) kernel.set_arg(first_index++, b);
  return first_index;
}

uint32_t WavefrontRenderer::max_samples_per_pass(uint32_t pixel_count) const {
  return max_samples_per_pass_for(ctx_.device(), pixel_count, aovs_);
}

void WavefrontRenderer::record(const char* label, EventHandle event) {
  if (event.get()) pending_.emplace_back(label, std::move(event));
}

void WavefrontRenderer::collect_times() {
  for (const auto& [label, event] : pending_) {
    StageTime& t = times_[label];
    t.label = label;
    t.seconds += ctx_.event_seconds(event);
    t.launches += 1;
  }
  pending_.clear();
}

std::vector<StageTime> WavefrontRenderer::stage_times() const {
  std::vector<StageTime> out;
  for (const auto& [label, t] : times_) out.push_back(t);
  return out;
}

// Kernel arguments follow wavefront.cl: each kernel's own arguments, then scratch, then state
// (and, for shading, the destination state of the survivors).
void WavefrontRenderer::generate(const GpuRenderParams& params, uint32_t job_begin,
                                 uint32_t slot_begin, uint32_t count) {
  generate_.set_arg(0, params);
  generate_.set_arg(1, *sample_slots_);
  generate_.set_arg(2, job_begin);
  generate_.set_arg(3, slot_begin);
  generate_.set_arg(4, count);
  bind(generate_, 5, state_);
  record("generate", ctx_.launch_profiled(generate_, count, local_size_, "wf_generate"));
}

// Closest hits, then shading, which stores the survivors densely into the other state set; swaps
// the sets and returns the number of survivors.
uint32_t WavefrontRenderer::intersect_and_shade(const GpuRenderParams& params, uint32_t active) {
  const cl_uint after_scene = bind_scene(intersect_, 0, scene_);
  intersect_.set_arg(after_scene, params);
  intersect_.set_arg(after_scene + 1, *sample_slots_);
  intersect_.set_arg(after_scene + 2, active);
  bind(intersect_, bind(intersect_, after_scene + 3, scratch_), state_);
  record("intersect", ctx_.launch_profiled(intersect_, active, local_size_, "wf_intersect"));
  const cl_uint zero = 0;
  ctx_.write_async(survivors_, &zero, sizeof zero);
  bind_scene(shade_, 0, scene_);
  shade_.set_arg(after_scene, params);
  shade_.set_arg(after_scene + 1, *sample_slots_);
  shade_.set_arg(after_scene + 2, active);
  shade_.set_arg(after_scene + 3, results_);
  shade_.set_arg(after_scene + 4, survivors_);
  bind(shade_, bind(shade_, bind(shade_, after_scene + 5, scratch_), state_), next_state_);
  record("shade", ctx_.launch_profiled(shade_, active, local_size_, "wf_shade"));
  cl_uint survivors = 0;
  ctx_.read(survivors_, &survivors, sizeof survivors);  // blocking: `zero` lives until here
  collect_times();
  std::swap(state_, next_state_);
  return survivors;
}

std::vector<GpuPixelPass> WavefrontRenderer::render_pass(const GpuRenderParams& params, const GpuSampleSlot* slots) {
  sample_slots_ = &upload_slots(ctx_, params, slots);
  const uint64_t jobs = uint64_t(params.pixel_count) * params.samples_per_pass;
  const size_t result_bytes = size_t(jobs) * result_bytes_per_job(aovs_);
  if (results_.bytes() < result_bytes) results_ = Buffer(ctx_, result_bytes, CL_MEM_READ_WRITE, "job results");

  uint32_t active = 0;
  uint64_t next_job = 0;
  while (next_job < jobs || active > 0) {
    // 1. Fill the free slots [active, paths) with the pass's next jobs.
    const uint32_t fresh = static_cast<uint32_t>(std::min<uint64_t>(paths_ - active, jobs - next_job));
    if (fresh > 0) generate(params, static_cast<uint32_t>(next_job), active, fresh);
    next_job += fresh;
    active += fresh;
    // 2. Closest hits, then shading: emission, scattering, or the end of the path; the
    //    survivors move to the front of the other set.
    active = intersect_and_shade(params, active);
  }

  // 4. Film: each pixel's samples summed in sample order.
  const size_t pass_bytes = size_t(params.pixel_count) * sizeof(GpuPixelPass);
  if (pass_.bytes() < pass_bytes) pass_ = Buffer(ctx_, pass_bytes, CL_MEM_WRITE_ONLY, "pass statistics");
  film_.set_arg(0, params);
  film_.set_arg(1, results_);
  film_.set_arg(2, pass_);
  record("film", ctx_.launch_profiled(film_, params.pixel_count, local_size_, "film_sum_jobs"));
  std::vector<GpuPixelPass> out(params.pixel_count);
  ctx_.read(pass_, out.data(), pass_bytes);
  collect_times();
  sum_aovs(ctx_, params, results_, local_size_);
  return out;
}

}  // namespace clpt
