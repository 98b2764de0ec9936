#include "render/megakernel_renderer.h"

#include <algorithm>

#include "render/limits.h"
#include "util/error.h"

namespace clpt {

MegakernelRenderer::MegakernelRenderer(DeviceContext& ctx, const DeviceScene& scene,
                                       const KernelFeatures& features, size_t local_size)
    : ctx_(ctx) {
  lockstep_group_ = features.lockstep_group;
  if (lockstep_group_ > ctx.device().max_work_group_size)
    throw Error(ExitCode::Usage, "--local-size " + std::to_string(lockstep_group_) + ": " + ctx.device().label() +
                                     " takes work-groups of at most " +
                                     std::to_string(ctx.device().max_work_group_size) + " work-items");
  local_size_ = lockstep_group_ ? lockstep_group_ : local_size;  // the plan sets both alike
  program_ = build(ctx, "megakernel.cl", features);
  kernel_ = entry_point(ctx, program_, "render_paths");
  film_ = entry_point(ctx, program_, "film_sum_jobs");
  prepare_aovs(ctx, program_, features);

  scene_ = upload_scene(ctx, scene);
}

uint32_t MegakernelRenderer::max_samples_per_pass(uint32_t pixel_count) const {
  return max_samples_per_pass_for(ctx_.device(), pixel_count, aovs_);
}

std::vector<GpuPixelPass> MegakernelRenderer::render_pass(const GpuRenderParams& params, const GpuSampleSlot* slots) {
  const size_t jobs = size_t(params.pixel_count) * params.samples_per_pass;
  const size_t result_bytes = jobs * result_bytes_per_job(aovs_);
  if (results_.bytes() < result_bytes) results_ = Buffer(ctx_, result_bytes, CL_MEM_READ_WRITE, "job results");
  const size_t bytes = size_t(params.pixel_count) * sizeof(GpuPixelPass);
  if (pass_.bytes() < bytes) pass_ = Buffer(ctx_, bytes, CL_MEM_WRITE_ONLY, "pass statistics");
  const cl_uint next = bind_scene(kernel_, 0, scene_);
  kernel_.set_arg(next, params);
  kernel_.set_arg(next + 1, upload_slots(ctx_, params, slots));
  kernel_.set_arg(next + 2, results_);
  film_.set_arg(0, params);
  film_.set_arg(1, results_);
  film_.set_arg(2, pass_);
  // A launch over part of the image (watchdog-sized, pass_loop.h) gets a fixed work-group size
  // when none was asked for: those launches vary in size, and a driver left to choose picks (and
  // PoCL compiles a kernel variant for, about a second each) a new work-group size for each.
  const bool whole_image =
      !params.slotted && params.pixel_begin == 0 && params.pixel_count == params.width * params.height;
  const size_t local_size = local_size_ || whole_image ? local_size_ : kPartialLaunchLocalSize;
  // The lockstep loop runs whole work-groups (megakernel.cl): round the launch up to them.
  const size_t global_size = lockstep_group_ ? (jobs + lockstep_group_ - 1) / lockstep_group_ * lockstep_group_ : jobs;
  ctx_.launch(kernel_, global_size, local_size, "render_paths");
  ctx_.launch(film_, params.pixel_count, local_size, "film_sum_jobs");
  std::vector<GpuPixelPass> out(params.pixel_count);
  ctx_.read(pass_, out.data(), bytes);
  sum_aovs(ctx_, params, results_, local_size);
  return out;
}

}  // namespace clpt
