#include "render/render_plan.h"

#include <algorithm>
#include <sstream>

#include "render/form_rule.h"
#include "render/megakernel_renderer.h"
#include "render/pass_schedule.h"
#include "render/wavefront_renderer.h"
#include "scene/device_textures.h"
#include "util/error.h"

namespace clpt {
namespace {

// When several devices share a pass, a range of the wavefront (which needs no watchdog bound)
// aims at a quarter of the pass loop's 0.5 s pass: enough ranges per pass to balance, few enough
// that each fills the device's paths in flight.
constexpr double kSharedRangeTargetS = 0.125;

// Launch sizing: the megakernel's launches are watchdog-sized (--launch-ms); a pass shared by
// several devices is cut into throughput-sized ranges whatever the form; otherwise the wavefront
// takes a whole pass in one launch (its launches are bounded by paths in flight).
LaunchSizing sizing_for(const DevicePlan& d, const RenderRequest& request, size_t device_count,
                        uint32_t image_pixels) {
  LaunchSizing sizing;
  const bool megakernel_split = d.form == ExecutionForm::Megakernel && request.launch_target_s > 0;
  sizing.target_s = megakernel_split ? request.launch_target_s : 0;
  if (!megakernel_split && device_count > 1) sizing.target_s = kSharedRangeTargetS;
  sizing.first_pixels = std::clamp(image_pixels / 64, 1u, 4096u);
  sizing.max_pixels =
      uint32_t(std::clamp<uint64_t>(launch_buffer_budget(d.device) / sizeof(GpuPixelPass), 1, UINT32_MAX));
  // A megakernel launch has a work-item per path (rounded up to its work-groups): under the width
  // at which the driver would compile the kernel again (cl_device.h), as the first launch is.
  const uint32_t limit = d.device.uniform_launch_limit();
  if (limit > 0 && d.form == ExecutionForm::Megakernel) {
    const uint32_t group = uint32_t(std::max<size_t>(d.local_size, 1));
    sizing.max_jobs = std::max(group, limit / group * group);
  }
  return sizing;
}

// ", half-films of A and B spp ...": how a Sobol render of the plan's sample count splits.
std::string half_films_line(const RenderPlan& plan) {
  const uint64_t half0 = half0_end(plan.target_spp, plan.sampler_granularity, true);
  return ", half-films of " + std::to_string(half0) + " and " + std::to_string(plan.target_spp - half0) +
         " spp (a power of two first: Sobol nets)";
}

}  // namespace

void check_precision_supported(Precision precision, const DeviceInfo& device) {
  if (precision == Precision::Double && !device.fp64)
    throw Error(ExitCode::DeviceError, "--precision double: " + device.label() +
                                      " does not report cl_khr_fp64 (no double precision); use "
                                      "--precision robust, or another device (`clpt devices`)");
}

GpuRenderParams make_params(const Scene& scene, const DeviceScene& ds) {
  const RenderSettings& s = scene.settings;
  GpuRenderParams p{};
  p.camera = ds.camera;
  p.width = static_cast<clpt_u32>(s.width);
  p.height = static_cast<clpt_u32>(s.height);
  p.sphere_count = ds.loop_spheres;
  p.max_bounces = static_cast<clpt_u32>(s.max_bounces);
  p.seed_lo = static_cast<clpt_u32>(s.seed & 0xffffffffu);
  p.seed_hi = static_cast<clpt_u32>(s.seed >> 32);
  static_assert(uint32_t(Sampler::Jitter) == CLPT_SAMPLER_JITTER && uint32_t(Sampler::Grid) == CLPT_SAMPLER_GRID &&
                    uint32_t(Sampler::Sobol) == CLPT_SAMPLER_SOBOL && uint32_t(Sampler::SobolGrid) == CLPT_SAMPLER_SOBOL_GRID,
                "Sampler's values are the kernels' CLPT_SAMPLER_*");
  p.sampler = static_cast<clpt_u32>(s.sampler);
  p.ray_epsilon = ds.ray_epsilon;
  p.pixel_begin = 0;
  p.pixel_count = p.width * p.height;
  p.estimator = parse_estimator(s.estimator).value_or(Estimator::Book) == Estimator::Nee ? CLPT_ESTIMATOR_NEE
                                                                                        : CLPT_ESTIMATOR_BOOK;
  p.rr_from = s.rr_from >= 0 ? static_cast<clpt_u32>(s.rr_from) : CLPT_RR_NEVER;
  p.light_count = static_cast<clpt_u32>(ds.lights.size());
  p.bvh_node_count = static_cast<clpt_u32>(ds.bvh.nodes.size());
  // The scene's own features, whatever kernel runs: the generic kernel must draw what a
  // specialised one fixes (the precision does not enter).
  p.scatter_draw_pairs = scatter_draws_paired(features_for_scene(scene)) ? 1u : 0u;
  return p;
}

RenderPlan plan_render(const RenderRequest& request, const std::vector<DeviceInfo>& devices) {
  const Scene& scene = request.scene;
  const RenderSettings& s = scene.settings;
  require_estimator_sees_lights(scene);
  RenderPlan plan;
  plan.width = s.width;
  plan.height = s.height;
  plan.image_pixels = uint32_t(s.width) * uint32_t(s.height);
  plan.target_spp = request.spp_given ? uint64_t(s.spp) : 0;
  plan.time_limit_s = request.time_limit_s;
  plan.target_error = request.target_error;
  plan.sampler_granularity = s.sampler == Sampler::Grid ? 16u : 1u;
  // Sobol nets come in powers of two (render/pass_schedule.h); a target error keeps equal
  // halves, whose difference estimates the error without bias (render/error_estimate.h).
  plan.power_of_two_halves = (s.sampler == Sampler::Sobol || s.sampler == Sampler::SobolGrid) && request.target_error == 0;
  plan.adaptive = request.adaptive;
  plan.precision = request.precision;
  plan.use_kernel_cache = request.use_kernel_cache;

  // What the scene needs (or everything, --generic); the device decides only the loop below.
  KernelFeatures features =
      request.generic_kernel ? generic_features(request.precision) : features_for_scene(scene, request.precision);
  features.intersection = request.intersection;
  features.megakernel_loop = request.megakernel_loop;
  features.scene_loops = request.scene_loops;
  features.cpu_vector_bits = request.cpu_vector_bits;
  features.sphere_reads = request.sphere_reads;
  features.aovs = request.aovs.any();  // the first-hit layers (--aovs): the render's request, not the scene's
  // The form rule reads the scene's own geometry, whatever kernel runs (render/form_rule.h).
  const KernelFeatures scene_features = request.generic_kernel ? features_for_scene(scene, request.precision) : features;

  for (size_t i = 0; i < devices.size(); ++i) {
    DevicePlan d;
    d.position = i;
    d.device = devices[i];
    const FormChoice choice = default_form_for(d.device, scene_features);
    d.form = request.form.value_or(choice.form);
    d.form_reason = request.form ? "--form" : choice.reason;
    d.features = features;
    d.features.unroll_scene_loops = scene_loops_unrolled_for(request.scene_loops, d.device);
    d.features.cpu_vector_lanes = cpu_vector_lanes_for(request.cpu_vector_bits, d.device);
    d.features.no_fast_gather = sphere_reads_by_select_for(request.sphere_reads, d.device, request.precision);
    if (d.form == ExecutionForm::Megakernel) {
      d.entry_file = "megakernel.cl";
      d.features.lockstep_group =
          lockstep_group_for(request.megakernel_loop, d.device, request.local_size);
      d.local_size = d.features.lockstep_group ? d.features.lockstep_group : request.local_size;
      // PoCL compiles a kernel per work-group size: left to choose, it picks a new one for each
      // whole-image launch size, so there every launch gets the partial launches' size.
      if (d.local_size == 0 && d.device.uniform_launch_limit() > 0)
        d.local_size = MegakernelRenderer::kPartialLaunchLocalSize;
    }
    // The meshes of large triangles in the loop beside the hierarchy only in the lockstep
    // megakernel, which runs the loop vectorised apart from the traversal: a path-at-a-time
    // kernel (the wavefront's intersect stage, the per-path loop) would run it scalar before the
    // traversal, slower than the hierarchy holding those triangles (docs/performance.md,
    // "Traversal").
    d.features.loop_beside_hierarchy_allowed = d.features.lockstep_group > 0;
    if (d.form == ExecutionForm::Wavefront) {
      d.entry_file = "wavefront.cl";
      d.local_size = request.local_size ? request.local_size : WavefrontRenderer::kDefaultLocalSize;
      d.paths_in_flight =
          request.paths_in_flight ? request.paths_in_flight : WavefrontRenderer::default_paths_in_flight(d.device);
    }
    d.kernel_cache = request.use_kernel_cache && !d.device.keeps_own_kernel_cache();
    // Every texel goes into one buffer: it must fit the device's largest allocation.
    if (d.device.max_alloc_bytes > 0) check_texture_memory(scene, d.device.max_alloc_bytes, "device '" + d.device.name + "'");
    d.sizing = sizing_for(d, request, devices.size(), plan.image_pixels);
    d.memory = estimate_device_memory(d.form, plan.image_pixels, scene.spheres.size(), d.paths_in_flight, d.device,
                                      triangle_count(scene), light_entry_bound(scene), environment_bytes_of(scene),
                                      d.features.aovs);
    plan.loop_meshes_apart = plan.loop_meshes_apart || d.features.loop_beside_hierarchy();
    plan.devices.push_back(std::move(d));
  }
  plan.textures = explain_textures(scene);
  return plan;
}

std::string explain_plan(const RenderPlan& plan, const std::vector<std::string>& vector_widths) {
  std::ostringstream o;
  o << "render plan: " << plan.width << "x" << plan.height << ", "
    << (plan.target_spp ? std::to_string(plan.target_spp) + " spp" : std::string("no sample limit"))
    << (plan.time_limit_s > 0 ? ", at most " + std::to_string(plan.time_limit_s) + " s" : std::string())
    << (plan.target_error > 0 ? ", until the estimated relative error is at most " +
                                    std::to_string(plan.target_error) : std::string())
    << (plan.adaptive ? ", adaptive sampling (half 1 where half 0's neighbours say the error is largest; "
                        "passes sized by the image alone)"
                      : std::string())
    << ", passes in multiples of " << plan.sampler_granularity << " sample(s) per pixel"
    << (plan.sampler_granularity > 1 ? " (the grid sampler's period)" : "")
    << (plan.power_of_two_halves && plan.target_spp > 0 ? half_films_line(plan) : std::string())
    << ", kernel cache "
    << (plan.use_kernel_cache ? "on" : "off (--no-cache)") << "\n";
  if (!plan.textures.empty()) o << "textures (docs/textures.md):\n" << plan.textures;
  for (const DevicePlan& d : plan.devices) {
    o << "device " << d.position << ": " << d.device.label() << "\n";
    if (plan.use_kernel_cache && !d.kernel_cache)
      o << "  kernel cache: the driver's own (clpt stores no binaries of this driver's: docs/cli.md)\n";
    o << "  execution form: " << execution_form_name(d.form) << " (" << d.form_reason << "), kernel file "
      << d.entry_file << "\n";
    if (d.form == ExecutionForm::Megakernel)
      o << "  megakernel loop: "
        << (d.features.lockstep_group
                ? "lockstep, work-groups of " + std::to_string(d.features.lockstep_group)
                : std::string("per path"))
        << " (--megakernel-loop " << megakernel_loop_name(d.features.megakernel_loop)
        << (d.features.megakernel_loop == MegakernelLoop::Auto
                ? std::string(": lockstep on CPUs, per path otherwise; this is a ") +
                      (d.device.is_cpu ? "CPU" : "GPU")
                : std::string())
        << ")\n";
    else
      o << "  path pool: " << d.paths_in_flight << " paths in flight\n";
    o << "  work-group size: "
      << (d.local_size ? std::to_string(d.local_size)
                       : std::string("the driver's choice for whole-image launches, ") +
                             std::to_string(MegakernelRenderer::kPartialLaunchLocalSize) + " for partial ones")
      << "\n";
    o << "  launches: "
      << (d.sizing.target_s > 0 ? "sized from the measured speed to take about " +
                                      std::to_string(int(d.sizing.target_s * 1000 + 0.5)) + " ms, the first " +
                                      std::to_string(d.sizing.first_pixels) + " pixels"
                                : std::string("one per pass"))
      << ", at most " << d.sizing.max_pixels << " pixels (device memory)"
      << (d.sizing.max_jobs != UINT32_MAX
              ? " and " + std::to_string(d.sizing.max_jobs) + " paths (the driver's one compiled kernel)"
              : std::string())
      << "\n";
    o << "  device memory: " << format_bytes(d.memory.total_bytes) << " (largest buffer '" << d.memory.largest_label
      << "', " << format_bytes(d.memory.largest_bytes) << ")\n";
    std::istringstream kernel(explain_kernel_options(d.features));
    for (std::string line; std::getline(kernel, line);) o << "  " << line << "\n";
    if (d.position < vector_widths.size()) o << "    vector width: " << vector_widths[d.position] << "\n";
  }
  return o.str();
}

}  // namespace clpt
