#include "render/wavefront_renderer.h"

#include <algorithm>
#include <chrono>
#include <numeric>

#include "kernels/kernel_source.h"
#include "kernels/path_state.h"

namespace clpt {
namespace {

// Kernel argument order shared with wavefront.cl: each kernel's own arguments, then the state.
constexpr cl_uint kGenerateStateArg = 7, kIntersectStateArg = 4, kShadeStateArg = 5,
                  kCompactStateArg = 5;

}  // namespace

uint32_t WavefrontRenderer::default_paths_in_flight(const DeviceInfo& device) {
  return std::clamp<uint32_t>(device.compute_units * 16384u, 65536u, 4u << 20);
}

WavefrontRenderer::WavefrontRenderer(DeviceContext& ctx, const DeviceScene& scene,
                                     const KernelFeatures& features, uint32_t paths_in_flight,
                                     size_t local_size)
    : ctx_(ctx),
      paths_(paths_in_flight ? paths_in_flight : default_paths_in_flight(ctx.device())),
      // A fixed work-group size: queue lengths change every launch, and a driver left to choose
      // would pick (and PoCL would compile a kernel variant for) a new size each time.
      local_size_(local_size ? local_size : kDefaultLocalSize) {
  build_options_ = kernel_build_options(features);
  const auto start = std::chrono::steady_clock::now();
  program_ = ctx.build_program(assemble_kernel_source("wavefront.cl"), build_options_, "wavefront.cl");
  build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  generate_ = Kernel(program_.get(), "wf_generate", ctx.where());
  intersect_ = Kernel(program_.get(), "wf_intersect", ctx.where());
  shade_ = Kernel(program_.get(), "wf_shade", ctx.where());
  compact_ = Kernel(program_.get(), "wf_compact", ctx.where());
  film_ = Kernel(program_.get(), "wf_film", ctx.where());

  spheres_ = Buffer(ctx, scene.spheres.size() * sizeof(GpuSphere), CL_MEM_READ_ONLY, "spheres");
  ctx.write(spheres_, scene.spheres.data(), scene.spheres.size() * sizeof(GpuSphere));
#define CLPT_ALLOCATE_STATE(type, name, bytes, doc) \
  state_.emplace_back(ctx, size_t(paths_) * (bytes), CL_MEM_READ_WRITE, "path state " #name);
  CLPT_PATH_STATE_FIELDS(CLPT_ALLOCATE_STATE)
#undef CLPT_ALLOCATE_STATE
  const size_t queue_bytes = size_t(paths_) * sizeof(cl_uint);
  active_ = Buffer(ctx, queue_bytes, CL_MEM_READ_WRITE, "active queue");
  next_active_ = Buffer(ctx, queue_bytes, CL_MEM_READ_WRITE, "next active queue");
  free_ = Buffer(ctx, queue_bytes, CL_MEM_READ_WRITE, "free queue");
  counters_ = Buffer(ctx, 2 * sizeof(cl_uint), CL_MEM_READ_WRITE, "queue counters");
  bind_state(generate_, kGenerateStateArg);
  bind_state(intersect_, kIntersectStateArg);
  bind_state(shade_, kShadeStateArg);
  bind_state(compact_, kCompactStateArg);
}

void WavefrontRenderer::bind_state(Kernel& kernel, cl_uint first_index) {
  for (size_t i = 0; i < state_.size(); ++i) kernel.set_arg(first_index + cl_uint(i), state_[i]);
}

uint32_t WavefrontRenderer::max_samples_per_pass(uint32_t pixel_count) const {
  return static_cast<uint32_t>(std::max<size_t>(1, kMaxJobBytes / sizeof(cl_float4) / pixel_count));
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

void WavefrontRenderer::generate(const GpuRenderParams& params, uint32_t job_begin, uint32_t count,
                                 uint32_t free_begin, uint32_t active_begin) {
  generate_.set_arg(0, params);
  generate_.set_arg(1, job_begin);
  generate_.set_arg(2, count);
  generate_.set_arg(3, free_);
  generate_.set_arg(4, free_begin);
  generate_.set_arg(5, active_);
  generate_.set_arg(6, active_begin);
  record("generate", ctx_.launch_profiled(generate_, count, local_size_, "wf_generate"));
}

std::vector<GpuPixelPass> WavefrontRenderer::render_pass(const GpuRenderParams& params) {
  const uint64_t jobs = uint64_t(params.pixel_count) * params.samples_per_pass;
  const size_t result_bytes = size_t(jobs) * sizeof(cl_float4);
  if (results_.bytes() < result_bytes) results_ = Buffer(ctx_, result_bytes, CL_MEM_READ_WRITE, "job results");

  // Every slot starts free.
  std::vector<cl_uint> all_slots(paths_);
  std::iota(all_slots.begin(), all_slots.end(), 0u);
  ctx_.write(free_, all_slots.data(), all_slots.size() * sizeof(cl_uint));
  uint32_t free_count = paths_, active_count = 0;
  uint64_t next_job = 0;
  cl_uint counters[2] = {0, 0};

  while (next_job < jobs || active_count > 0) {
    // 1. Refill free slots with the pass's next jobs (taken from the free queue's end).
    const uint32_t fresh = static_cast<uint32_t>(std::min<uint64_t>(free_count, jobs - next_job));
    if (fresh > 0) {
      generate(params, static_cast<uint32_t>(next_job), fresh, free_count - fresh, active_count);
      next_job += fresh;
      free_count -= fresh;
      active_count += fresh;
    }
    // 2. Closest hits of the active paths.
    intersect_.set_arg(0, spheres_);
    intersect_.set_arg(1, params);
    intersect_.set_arg(2, active_);
    intersect_.set_arg(3, active_count);
    record("intersect", ctx_.launch_profiled(intersect_, active_count, local_size_, "wf_intersect"));
    // 3. Shading: emission, scattering, or the end of the path.
    shade_.set_arg(0, spheres_);
    shade_.set_arg(1, params);
    shade_.set_arg(2, active_);
    shade_.set_arg(3, active_count);
    shade_.set_arg(4, results_);
    record("shade", ctx_.launch_profiled(shade_, active_count, local_size_, "wf_shade"));
    // 4. Compaction: survivors to the next active queue, ended paths' slots back to the free queue.
    counters[0] = 0;
    counters[1] = free_count;
    ctx_.write_async(counters_, counters, sizeof counters);
    compact_.set_arg(0, active_);
    compact_.set_arg(1, active_count);
    compact_.set_arg(2, next_active_);
    compact_.set_arg(3, free_);
    compact_.set_arg(4, counters_);
    record("compact", ctx_.launch_profiled(compact_, active_count, local_size_, "wf_compact"));
    ctx_.read(counters_, counters, sizeof counters);
    collect_times();
    active_count = counters[0];
    free_count = counters[1];
    std::swap(active_, next_active_);
  }

  // 5. Film: each pixel's samples summed in sample order.
  const size_t pass_bytes = size_t(params.pixel_count) * sizeof(GpuPixelPass);
  if (pass_.bytes() < pass_bytes) pass_ = Buffer(ctx_, pass_bytes, CL_MEM_WRITE_ONLY, "pass statistics");
  film_.set_arg(0, params);
  film_.set_arg(1, results_);
  film_.set_arg(2, pass_);
  record("film", ctx_.launch_profiled(film_, params.pixel_count, local_size_, "wf_film"));
  std::vector<GpuPixelPass> out(params.pixel_count);
  ctx_.read(pass_, out.data(), pass_bytes);
  collect_times();
  return out;
}

}  // namespace clpt
