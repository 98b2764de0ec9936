#include "render/render_session.h"

#include <algorithm>

#include "cl/cl_device.h"
#include "render/rank_group.h"
#include "scene/device_scene.h"
#include "util/clock.h"
#include "util/error.h"

namespace clpt {
namespace {

PassLoopOptions pass_loop_options(const RenderPlan& plan, const RenderRequest& request) {
  PassLoopOptions o;
  o.request.target_spp = plan.target_spp;
  o.request.time_limit_s = plan.time_limit_s;
  o.request.target_error = plan.target_error;
  o.request.granularity = plan.sampler_granularity;
  o.request.power_of_two_halves = plan.power_of_two_halves;
  o.request.adaptive = plan.adaptive;
  o.interrupt = request.interrupt;
  o.checkpoint = request.checkpoint;
  o.checkpoint_every_s = request.checkpoint_every_s;
  o.show_progress = request.show_progress;
  return o;
}

// The devices' parts, and the first device that built for the form, options and path pool.
void report_devices(const RenderPlan& plan, const DevicePool& pool, RenderReport& report) {
  report.devices = pool.shares();
  report.stage_times = pool.stage_times();
  report.kernel_cache = pool.kernel_cache();
  bool first = true;
  for (size_t i = 0; i < report.devices.size(); ++i) {
    const DeviceShare& share = report.devices[i];
    report.launches += share.launches;
    if (!share.built) continue;  // failed its set-up
    if (!report.device.empty()) report.device += " + ";
    report.device += share.device;
    report.build_seconds = std::max(report.build_seconds, share.build_seconds);
    if (!first) continue;
    first = false;
    report.form = plan.devices[i].form;
    report.build_options = kernel_build_options(plan.devices[i].features);
    report.paths_in_flight = plan.devices[i].paths_in_flight;
  }
}

}  // namespace

Film run_render(const RenderRequest& request, RenderReport& report) {
  const Scene& scene = request.scene;
  const RenderSettings& settings = scene.settings;

  check_scene_limits(scene);  // before any device work: fails fast and allocates nothing

  // 1. The devices (one, or several sharing every pass) and every decision of the render; the
  //    ranks of an MPI job check that they all render the same thing.
  const Clock::time_point discovery_start = Clock::now();
  const RenderPlan plan = plan_render(request, select_devices(list_devices(), request.device));
  report.discovery_seconds = seconds_since(discovery_start);
  RankGroup* ranks = request.ranks && request.ranks->size() > 1 ? request.ranks : nullptr;
  if (ranks) check_ranks_agree(*ranks, render_identity(request, plan));
  const bool coordinator = !ranks || ranks->coordinator();
  if (request.on_plan && coordinator) request.on_plan(plan);

  // 2. The scene as the kernels see it; on each device a context and a kernel built as planned,
  //    in parallel, and launched once apart from the passes (DevicePool::warm_up: what a driver
  //    compiles at a first launch). A rank whose devices all fail takes no part; the others carry on.
  const Clock::time_point convert_start = Clock::now();
  const DeviceScene device_scene = make_device_scene(scene, settings.width, settings.height, request.precision,
                                                     BvhBuilder::Clpt, plan.loop_meshes_apart);
  report.convert_seconds = seconds_since(convert_start);
  const FaultPlan faults = request.faults ? *request.faults : FaultPlan::from_environment();
  std::unique_ptr<DevicePool> pool;
  std::string failure;
  const GpuRenderParams params = make_params(scene, device_scene);
  try {
    pool = std::make_unique<DevicePool>(plan, device_scene, faults);
    report.first_launch_seconds = pool->warm_up(params);
  } catch (const Error& e) {
    if (!ranks) throw;
    failure = e.what();
    pool.reset();
  }
  std::unique_ptr<RankPassTracer> rank_tracer;
  std::unique_ptr<DevicePoolTracer> pool_tracer;
  if (ranks)
    rank_tracer = std::make_unique<RankPassTracer>(*ranks, pool.get(), failure, plan.image_pixels, faults, request.interrupt);
  else
    pool_tracer = std::make_unique<DevicePoolTracer>(*pool);
  PassTracer& tracer = ranks ? static_cast<PassTracer&>(*rank_tracer) : *pool_tracer;
  report.precision = request.precision;

  // 3. Passes until the sample count or the time budget is reached, or an interrupt.
  Film film = request.resume && coordinator ? *request.resume : Film(settings.width, settings.height);
  if (request.aovs.any()) {  // the first-hit layers (--aovs): a checkpoint carries none to resume
    if (request.resume) throw Error(ExitCode::Usage, "--aovs: a resumed render cannot have first-hit layers");
    film.enable_aovs();
  }
  const Film::Totals before = film.totals();  // a resumed film's samples are not this run's
  const auto t0 = Clock::now();
  const PassLoopResult passes = run_passes(tracer, params, film, pass_loop_options(plan, request));

  // 4. What happened.
  report.render_seconds = seconds_since(t0);
  report.pass_seconds = passes.trace_seconds;
  report.passes = passes.passes;
  report.interrupted = passes.interrupted;
  report.stop = passes.stop;
  report.estimate = passes.estimate;
  report.spp = film.samples_per_pixel();
  report.paths = film.total_samples() - before.total_samples;
  report.segments = film.total_segments() - before.total_segments;
  report.dropped = film.dropped_samples();
  if (pool) report_devices(plan, *pool, report);
  if (ranks) report.ranks = rank_tracer->gather_shares();
  return film;
}

}  // namespace clpt
