#include "render/render_session.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "cl/cl_context.h"
#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "render/megakernel_renderer.h"
#include "render/progress.h"
#include "render/wavefront_renderer.h"
#include "scene/device_scene.h"

namespace clpt {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

GpuRenderParams make_params(const Scene& scene, const DeviceScene& ds) {
  const RenderSettings& s = scene.settings;
  GpuRenderParams p{};
  p.camera = ds.camera;
  p.width = static_cast<clpt_u32>(s.width);
  p.height = static_cast<clpt_u32>(s.height);
  p.sphere_count = static_cast<clpt_u32>(ds.spheres.size());
  p.max_bounces = static_cast<clpt_u32>(s.max_bounces);
  p.seed_lo = static_cast<clpt_u32>(s.seed & 0xffffffffu);
  p.seed_hi = static_cast<clpt_u32>(s.seed >> 32);
  p.sampler = s.sampler == Sampler::Grid ? CLPT_SAMPLER_GRID : CLPT_SAMPLER_JITTER;
  p.ray_epsilon = ds.ray_epsilon;
  p.pixel_begin = 0;
  p.pixel_count = p.width * p.height;
  return p;
}

std::unique_ptr<Renderer> make_renderer(ExecutionForm form, DeviceContext& ctx,
                                        const DeviceScene& scene, const KernelFeatures& features,
                                        uint32_t paths_in_flight, size_t local_size) {
  if (form == ExecutionForm::Wavefront)
    return std::make_unique<WavefrontRenderer>(ctx, scene, features, paths_in_flight, local_size);
  return std::make_unique<MegakernelRenderer>(ctx, scene, features, local_size);
}

const char* execution_form_name(ExecutionForm form) {
  return form == ExecutionForm::Wavefront ? "wavefront" : "megakernel";
}

// CPUs (PoCL): the wavefront, whose loop-free stage kernels PoCL vectorises across work-items
// while the megakernel's per-path loop stays scalar (measured with `clpt bench`, README "Speed").
// GPUs: the megakernel, which keeps paths in registers; no GPU has been measured yet.
ExecutionForm default_form_for(const DeviceInfo& device) {
  return device.is_cpu ? ExecutionForm::Wavefront : ExecutionForm::Megakernel;
}

uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity) {
  double want = samples_per_pixel_per_s > 0 ? samples_per_pixel_per_s * target_s : granularity;
  want = std::clamp(want, double(granularity), double(kMaxSamplesPerPass));
  uint64_t n = uint64_t(want) / granularity * granularity;
  if (target > 0) n = std::min<uint64_t>(n, target - done);
  return static_cast<uint32_t>(std::max<uint64_t>(n, 1));
}

Film run_render(const RenderRequest& request, RenderReport& report) {
  const Scene& scene = request.scene;
  const RenderSettings& settings = scene.settings;

  // 1. The device, and a context on it.
  const std::vector<DeviceInfo> devices = list_devices();
  DeviceContext ctx(select_device(devices, request.device));
  report.device = ctx.where();

  // 2. The scene as the kernels see it, and a kernel specialised for it.
  const DeviceScene device_scene = make_device_scene(scene, settings.width, settings.height);
  const KernelFeatures features = request.generic_kernel ? generic_features() : features_for_scene(scene);
  report.form = request.form.value_or(default_form_for(ctx.device()));
  const std::unique_ptr<Renderer> renderer = make_renderer(
      report.form, ctx, device_scene, features, request.paths_in_flight, request.local_size);
  report.build_options = renderer->build_options();
  report.build_seconds = renderer->build_seconds();
  if (auto* wavefront = dynamic_cast<WavefrontRenderer*>(renderer.get()))
    report.paths_in_flight = wavefront->paths_in_flight();

  // 3. Passes until the sample count or the time budget is reached.
  Film film(settings.width, settings.height);
  GpuRenderParams params = make_params(scene, device_scene);
  const uint64_t target = request.spp_given ? uint64_t(settings.spp) : 0;
  const uint32_t granularity = settings.sampler == Sampler::Grid ? 16u : 1u;
  const double pass_target_s = 0.5;
  Progress progress(request.show_progress);
  const auto t0 = std::chrono::steady_clock::now();
  double rate = 0;  // samples per pixel per second
  while (target == 0 || film.samples_per_pixel() < target) {
    const double elapsed = seconds_since(t0);
    if (request.time_limit_s > 0 && report.passes > 0 && elapsed >= request.time_limit_s) break;
    double pass_s = pass_target_s;
    if (request.time_limit_s > 0) pass_s = std::min(pass_s, std::max(0.0, request.time_limit_s - elapsed));
    params.sample_begin = static_cast<clpt_u32>(film.samples_per_pixel());
    params.samples_per_pass = std::min(
        next_pass_samples(film.samples_per_pixel(), target, rate, pass_s, granularity),
        std::max(granularity, renderer->max_samples_per_pass(params.pixel_count) / granularity * granularity));
    const auto pass_start = std::chrono::steady_clock::now();
    film.add_pass(renderer->render_pass(params), 0, params.samples_per_pass);
    rate = params.samples_per_pass / std::max(1e-9, seconds_since(pass_start));
    ++report.passes;
    progress.update(report.passes, film.samples_per_pixel(), target,
                    double(film.total_samples()) / std::max(1e-9, seconds_since(t0)),
                    seconds_since(t0), request.time_limit_s);
  }
  progress.finish();
  report.render_seconds = seconds_since(t0);
  report.spp = film.samples_per_pixel();
  report.paths = film.total_samples();
  report.segments = film.total_segments();
  report.dropped = film.dropped_samples();
  report.stage_times = renderer->stage_times();
  return film;
}

}  // namespace clpt
