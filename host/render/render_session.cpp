#include "render/render_session.h"

#include <algorithm>
#include <chrono>
#include <memory>

#include "cl/cl_context.h"
#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "render/device_pool.h"
#include "render/fault_injection.h"
#include "render/limits.h"
#include "render/megakernel_renderer.h"
#include "render/pass_loop.h"
#include "render/wavefront_renderer.h"
#include "scene/device_scene.h"
#include "util/error.h"
#include "util/clock.h"

namespace clpt {
namespace {

PassLoopOptions pass_loop_options(const RenderRequest& request) {
  const RenderSettings& settings = request.scene.settings;
  PassLoopOptions o;
  o.target_spp = request.spp_given ? uint64_t(settings.spp) : 0;
  o.time_limit_s = request.time_limit_s;
  o.granularity = settings.sampler == Sampler::Grid ? 16u : 1u;
  o.interrupt = request.interrupt;
  o.checkpoint = request.checkpoint;
  o.after_first_pass = request.after_first_pass;
  o.checkpoint_every_s = request.checkpoint_every_s;
  o.show_progress = request.show_progress;
  return o;
}

PoolSettings pool_settings(const RenderRequest& request, const DeviceScene& device_scene) {
  const Scene& scene = request.scene;
  PoolSettings s;
  s.scene = &device_scene;
  s.features = request.generic_kernel ? generic_features(request.precision)
                                      : features_for_scene(scene, request.precision);
  s.features.intersection = request.intersection;
  s.features.megakernel_loop = request.megakernel_loop;
  s.features.scene_loops = request.scene_loops;
  s.form = request.form;
  s.paths_in_flight = request.paths_in_flight;
  s.local_size = request.local_size;
  s.use_kernel_cache = request.use_kernel_cache;
  s.launch_target_s = request.launch_target_s;
  s.image_pixels = uint32_t(scene.settings.width) * uint32_t(scene.settings.height);
  s.faults = FaultPlan::from_environment();
  return s;
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
  p.estimator = parse_estimator(s.estimator).value_or(Estimator::Book) == Estimator::Nee ? CLPT_ESTIMATOR_NEE
                                                                                        : CLPT_ESTIMATOR_BOOK;
  p.rr_from = s.rr_from >= 0 ? static_cast<clpt_u32>(s.rr_from) : CLPT_RR_NEVER;
  p.light_count = static_cast<clpt_u32>(ds.lights.size());
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

void check_precision_supported(Precision precision, const DeviceInfo& device) {
  if (precision == Precision::Double && !device.fp64)
    throw Error(ExitCode::DeviceError, "--precision double: " + device.label() +
                                      " does not report cl_khr_fp64 (no double precision); use "
                                      "--precision robust, or another device (`clpt devices`)");
}

// The megakernel everywhere. On CPUs (PoCL) it runs its lockstep loop, which PoCL vectorises
// across work-items with no path state in memory: measured 4x the wavefront's paths/s with
// `clpt bench` (README "Speed"); the wavefront's stages move every path's state through memory
// at every bounce. GPUs run the per-path loop, which keeps paths in registers; no GPU has been
// measured yet.
ExecutionForm default_form_for(const DeviceInfo& device) {
  (void)device;
  return ExecutionForm::Megakernel;
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

  check_scene_limits(scene);  // before any device work: fails fast and allocates nothing

  // 1. The devices (one, or several sharing every pass), and the scene as the kernels see it.
  const std::vector<DeviceInfo> devices = select_devices(list_devices(), request.device);
  const DeviceScene device_scene = make_device_scene(scene, settings.width, settings.height, request.precision);

  // 2. On each device a context and a kernel specialised for the scene, built in parallel.
  DevicePool pool(devices, pool_settings(request, device_scene));
  report.precision = request.precision;

  // 3. Passes until the sample count or the time budget is reached, or an interrupt.
  Film film = request.resume ? *request.resume : Film(settings.width, settings.height);
  const Film::Totals before = film.totals();  // a resumed film's samples are not this run's
  const auto t0 = Clock::now();
  run_passes(pool, make_params(scene, device_scene), film, pass_loop_options(request), report);
  report.render_seconds = seconds_since(t0);
  report.spp = film.samples_per_pixel();
  report.paths = film.total_samples() - before.total_samples;
  report.segments = film.total_segments() - before.total_segments;
  report.dropped = film.dropped_samples();
  pool.fill_report(report);
  return film;
}

}  // namespace clpt
