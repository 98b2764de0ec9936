// `clpt render SCENE`: load the scene, apply command-line overrides, render, write the outputs.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/render_summary.h"
#include "kernels/kernel_options.h"
#include "render/checkpoint.h"
#include "render/film_raw.h"
#include "render/limits.h"
#include "render/rank_group.h"
#include "render/render_session.h"
#include "scene/environment.h"
#include "scene/precision_range.h"
#include "scene/scene_image.h"
#include "scene/scene_loader.h"
#include "tools/vector_width.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/interrupt.h"
#ifdef CLPT_WITH_OIIO
#include "io/exr_writer.h"
#include "io/image_io.h"
#include "io/render_file.h"
#endif

namespace clpt {
namespace {

struct RenderOptions {
  std::string scene_path;
  std::string output;
  std::string exr_compression = "zip";  // --exr-compression (io/exr_writer.h)
  std::optional<int64_t> spp;
  std::optional<double> time_s;
  std::optional<double> target_error;  // --target-error, relative RMSE
  std::optional<uint64_t> seed;
  std::string device;
  std::optional<int> width, height, max_bounces;
  std::optional<std::string> camera;  // --camera (glTF scenes)
  std::optional<std::string> sampler;
  std::string precision = "robust";
  std::optional<std::string> intersection;
  std::optional<std::string> estimator, light_sampling;
  std::optional<int> rr_from;
  EnvironmentOverrides environment;  // --environment, --environment-strength, --environment-rotation
  double exposure_ev = 0;            // --exposure (the PNG preview only)
  std::string tonemap = "clamp";     // --tonemap (the PNG preview only)
  bool quiet = false;
  bool progress = false;
  bool explain = false;
  bool generic = false;
  bool adaptive = false;  // --adaptive
  bool no_cache = false;
  std::string form = "auto";
  std::string megakernel_loop = "auto";
  std::string scene_loops = "auto";
  std::string cpu_vector_bits = "auto";
  std::string sphere_reads = "auto";
  uint32_t paths_in_flight = 0;
  size_t local_size = 0;
  double launch_ms = 75;          // megakernel launch target, milliseconds; 0: one per pass
  std::string checkpoint;         // --checkpoint FILE ("" = none)
  double checkpoint_every_s = 60;
  std::string resume;             // --resume FILE ("" = none)
  std::string aovs;               // --aovs LIST ("" = none): first-hit layers for denoisers
  AovSet requested_aovs;          // parsed from `aovs` by run()
};

// --aovs: the layers asked for, checked against the outputs that must carry them (before any
// work). They live in the EXR and in no checkpoint: a raw .pfm film, --checkpoint and --resume
// cannot have them.
AovSet requested_aovs(const RenderOptions& o, const std::string& out) {
  if (o.aovs.empty()) return {};
  const std::string what = "--aovs " + o.aovs;
  const AovSet set = parse_aov_set(o.aovs, what);
  if (!out.empty() && std::filesystem::path(out).extension() == ".pfm")
    throw Error(ExitCode::Usage, what + ": the layers are written as channels of the EXR; -o " + out +
                                     " is a raw .pfm film, which holds the radiance only (write an .exr)");
  if (!o.checkpoint.empty())
    throw Error(ExitCode::Usage, what + ": a checkpoint keeps no first-hit layers; render with --aovs "
                                        "without --checkpoint");
  if (!o.resume.empty())
    throw Error(ExitCode::Usage, what + ": the checkpoint " + o.resume +
                                     " holds no first-hit layers to continue; render with --aovs without --resume");
  return set;
}

// Where the outputs go: -o, else SCENE_STEM.exr in the current directory. Checked before any work.
std::string output_path(const RenderOptions& o) {
  std::string path = o.output;
  if (path.empty()) path = std::filesystem::path(o.scene_path).stem().string() + ".exr";
  const std::string ext = std::filesystem::path(path).extension().string();
#ifdef CLPT_WITH_OIIO
  if (ext != ".exr" && ext != ".pfm")
    throw Error(ExitCode::Usage, "-o " + path + ": the output must be an .exr (or a raw .pfm) file");
#else
  if (ext != ".pfm")
    throw Error(ExitCode::Usage, "-o " + path + ": this clpt was built without OpenImageIO "
                                 "(CLPT_WITH_OIIO=OFF) and writes only raw .pfm films");
#endif
  check_output_file("-o", path);  // the PNG preview goes beside it
  return path;
}

void apply_overrides(const RenderOptions& o, RenderSettings& s) {
  if (o.spp) s.spp = *o.spp;
  if (o.seed) s.seed = *o.seed;
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.max_bounces) s.max_bounces = *o.max_bounces;
  if (o.sampler) s.sampler = sampler_from_name(*o.sampler).value();  // CLI11 checked the name
  if (o.estimator) s.estimator = *o.estimator;
  if (o.rr_from) s.rr_from = *o.rr_from;
  if (o.light_sampling) s.light_sampling = *o.light_sampling;
  if (s.sampler == Sampler::Grid && (o.spp || (!o.time_s && !o.target_error)) && s.spp % 16 != 0)
    throw Error(ExitCode::Usage, "--spp " + std::to_string(s.spp) +
                                     ": the grid sampler needs a multiple of 16 samples per pixel "
                                     "(--sampler jitter takes any count)");
}

#ifdef CLPT_WITH_OIIO
// The EXR's record of where the time went: the summary's figures as they stand now, before the
// EXR itself is written (io/render_file.h, clpt:elapsed_s).
void add_times(RenderFileInfo& info, const RenderReport& report, const RenderCommandTimes& times) {
  const RenderTimeSplit s = render_time_split(report, times);
  info.paths = report.paths;
  info.segments = report.segments;
  info.passes_s = s.passes;
  info.paths_per_s = double(report.paths) / std::max(1e-9, s.passes);
  info.segments_per_s = double(report.segments) / std::max(1e-9, s.passes);
  info.scene_load_s = s.scene_load;
  if (s.image_load > 0) info.image_load_s = s.image_load;
  if (s.resume_load > 0) info.resume_load_s = s.resume_load;
  info.discovery_s = s.discovery;
  info.convert_s = s.convert;
  info.kernel_build_s = s.kernel_build;
  info.kernel_build = kernel_build_source(report);
  info.first_launch_s = s.first_launch;
  info.output_s = s.output;
  info.elapsed_s = s.wall;
}
#endif

// scene, report and times feed the EXR metadata only (unused in the OIIO-free build).
void write_outputs(const RenderOptions& o, const std::string& path, const Film& film,
                   [[maybe_unused]] const Scene& scene, [[maybe_unused]] const RenderReport& report,
                   [[maybe_unused]] const RenderCommandTimes& times) {
  const bool quiet = o.quiet;
  const std::string ext = std::filesystem::path(path).extension().string();
  std::string written = path;
  if (ext == ".pfm") {
    write_film_pfm(path, film);
    written += " (and its .var.pfm)";
  } else {
#ifdef CLPT_WITH_OIIO
    RenderFileInfo info;
    info.version = CLPT_VERSION;
    info.spp = report.spp;  // interrupted: the finished passes
    info.seed = scene.settings.seed;
    info.scene = scene.file;
    info.scene_hash = scene.file_hash;
    info.device = report.device;
    info.precision = precision_name(report.precision);
    info.rr_from = scene.settings.rr_from;
    info.estimator = scene.settings.estimator;
    info.sampler = sampler_name(scene.settings.sampler);
    info.adaptive = o.adaptive;
    info.max_bounces = uint64_t(scene.settings.max_bounces);
    info.preview_exposure = o.exposure_ev;
    info.preview_tonemap = o.tonemap;
    info.dropped_samples = report.dropped;
    info.interrupted = report.interrupted;
    if (report.estimate.valid) info.error_estimate = report.estimate.relative_rmse_upper;
    info.target_error = o.target_error;
    if (report.stop != StopReason::None) info.stop = stop_reason_name(report.stop);
    info.aovs = aov_set_text(o.requested_aovs);
    add_times(info, report, times);
    written += " and " + write_render_file(path, film, info, o.exr_compression);
#endif
  }
  if (!quiet) std::printf("wrote %s\n", written.c_str());
}

// --resume: the checkpoint's film, checked against this render (exit 2 on any mismatch).
// --checkpoint: a callback saving the film between passes. Both before any device work; `times`
// takes the checkpoint's load and the saves.
void prepare_resume_and_checkpoints(const RenderOptions& o, const Scene& scene, RenderRequest& request,
                                    RenderCommandTimes& times) {
  if (!o.resume.empty()) {
    const Clock::time_point start = Clock::now();
    request.resume = load_checkpoint(o.resume, scene, o.adaptive);
    times.resume_load = seconds_since(start);
    const uint64_t done = request.resume->samples_per_pixel();
    if (request.spp_given && done > uint64_t(scene.settings.spp))
      throw Error(ExitCode::Usage, "--spp " + std::to_string(scene.settings.spp) + ": the checkpoint " +
                                       o.resume + " already holds " + std::to_string(done) +
                                       " samples per pixel");
  }
  if (o.checkpoint.empty()) return;
  request.checkpoint_every_s = o.checkpoint_every_s;
  request.checkpoint = [path = o.checkpoint, &scene, adaptive = o.adaptive, &times](const Film& film) {
    const Clock::time_point start = Clock::now();
    save_checkpoint(path, scene, film, adaptive);
    times.output += seconds_since(start);
  };
}

// After the passes: the final checkpoint, then the image of every finished pass. Returns the exit
// code: Interrupted (130) whenever SIGINT/SIGTERM arrived, even if the last pass completed.
int finish_outputs(const RenderOptions& o, const std::string& out, const Film& film, const Scene& scene,
                   const RenderReport& report, RenderCommandTimes& times) {
  const bool signalled = interrupt_flag().load();
  const unsigned long long spp = film.samples_per_pixel();
  if (spp == 0) {  // interrupted before the first pass finished (and nothing resumed)
    std::fprintf(stderr, "clpt: interrupted before any pass finished; nothing written\n");
    return static_cast<int>(ExitCode::Interrupted);
  }
  if (!o.checkpoint.empty()) {
    const Clock::time_point start = Clock::now();
    save_checkpoint(o.checkpoint, scene, film, o.adaptive);
    times.output += seconds_since(start);
    if (!o.quiet) std::printf("wrote checkpoint %s (%llu spp)\n", o.checkpoint.c_str(), spp);
  }
  const Clock::time_point start = Clock::now();
  write_outputs(o, out, film, scene, report, times);
  times.output += seconds_since(start);
  if (!signalled) return 0;
  std::fprintf(stderr, "clpt: interrupted: wrote the %llu finished samples per pixel%s\n", spp,
               report.interrupted ? "" : " (the render had completed)");
  return static_cast<int>(ExitCode::Interrupted);
}

// A rank other than 0 of an MPI job: renders its parts and writes nothing; its exit code is rank
// 0's, sent once rank 0 has written the outputs (so that no rank leaves the job before rank 0
// knows whether the outputs could be written).
int run_as_worker(RankGroup& ranks, const RenderRequest& request) {
  RenderReport report;
  run_render(request, report);
  std::vector<uint8_t> code;
  ranks.broadcast(code);
  return code.empty() ? static_cast<int>(ExitCode::Failure) : int(code[0]);
}

int run(RenderOptions o) {
  RenderCommandTimes times;
  // Under an MPI launcher: the job's ranks (loads MPI); otherwise this process alone.
  RankGroup& ranks = process_rank_group();
  const bool writes = ranks.coordinator();  // rank 0 alone checks and writes the outputs
  const std::string out = writes ? output_path(o) : "";
  o.requested_aovs = requested_aovs(o, out);
  const Precision precision = *parse_precision(o.precision);  // CLI11 checked the word
  if (writes && !o.checkpoint.empty()) check_output_file("--checkpoint", o.checkpoint);
  const Clock::time_point load_start = Clock::now();
  const double images_before = scene_image_seconds();
  Scene scene = load_scene_file(o.scene_path, GltfView{o.camera, o.width, o.height});
  apply_overrides(o, scene.settings);
  // A scene with no light of its own is lit by the default environment (before the environment
  // options, which may then scale or turn it), unless --environment names one or none.
  const std::string default_light = o.environment.file ? "" : light_unlit_scene(scene);
  apply_environment_overrides(scene, o.environment);
  check_scene_limits(scene, {o.width || o.height, o.spp.has_value(), o.max_bounces.has_value()});
  times.image_load = scene_image_seconds() - images_before;
  times.scene_load = seconds_since(load_start) - times.image_load;

  RenderRequest request;
  request.device = o.device;
  request.time_limit_s = o.time_s.value_or(0.0);
  request.target_error = o.target_error.value_or(0.0);
  request.spp_given = o.spp.has_value() || (!o.time_s && !o.target_error);
  request.adaptive = o.adaptive;
  request.generic_kernel = o.generic;
  request.precision = precision;
  if (o.intersection) request.intersection = parse_intersection(*o.intersection);
  if (o.form != "auto")
    request.form = o.form == "wavefront" ? ExecutionForm::Wavefront : ExecutionForm::Megakernel;
  request.megakernel_loop = *parse_megakernel_loop(o.megakernel_loop);  // CLI11 checked the word
  request.scene_loops = *parse_scene_loops(o.scene_loops);
  request.cpu_vector_bits = *parse_cpu_vector_bits(o.cpu_vector_bits);
  request.sphere_reads = *parse_sphere_reads(o.sphere_reads);
  request.paths_in_flight = o.paths_in_flight;
  request.local_size = o.local_size;
  request.use_kernel_cache = !o.no_cache;
  request.aovs = o.requested_aovs;
  request.show_progress = writes && !o.quiet && (o.progress || ::isatty(STDERR_FILENO));
  request.ranks = &ranks;
  request.launch_target_s = o.launch_ms / 1000;
  // After device selection, before any device work: the plan as every device will run it.
  // --explain also measures each device's vector width (a child render per device,
  // tools/vector_width.h); the request is the one rendered, as it stands when the plan is made.
  if (o.explain)
    request.on_plan = [&request](const RenderPlan& plan) {
      std::vector<std::string> widths;
      for (const DevicePlan& d : plan.devices)
        widths.push_back(probe_vector_width(request, d, this_executable()).describe());
      std::printf("%s", explain_plan(plan, widths).c_str());
    };
  RenderReport report;
  request.scene = scene;
  // The loader's findings (e.g. degenerate triangles dropped), then scenes beyond what the
  // extreme-scene tests proved for this preset (README "Numerical extremes").
  if (!o.quiet && writes) {
    std::vector<std::string> warnings = scene.warnings;
    if (!default_light.empty()) warnings.push_back(default_light);
    if (std::string unlit = unlit_scene_warning(scene); !unlit.empty()) warnings.push_back(std::move(unlit));
    if (scene.environment && !scene.environment->notice.empty()) warnings.push_back(scene.environment->notice);
    for (std::string& warning : precision_range_warnings(scene, request.precision)) warnings.push_back(std::move(warning));
    for (const std::string& warning : warnings) std::fprintf(stderr, "clpt: warning: %s\n", warning.c_str());
  }
  install_interrupt_handlers(writes ? InterruptNotes::Print : InterruptNotes::Silent);
  request.interrupt = &interrupt_flag();
  if (!writes) return run_as_worker(ranks, request);
  prepare_resume_and_checkpoints(o, scene, request, times);
  const Film film = run_render(request, report);
  if (!o.quiet) print_render_summary(scene, report);
  const int code = finish_outputs(o, out, film, scene, report, times);  // throws: main ends the job
  if (!o.quiet) print_render_times(report, times);
  std::vector<uint8_t> code_for_workers = {uint8_t(code)};
  ranks.broadcast(code_for_workers);
  return code;
}

}  // namespace

std::function<int()> add_render_command(CLI::App& app) {
  auto o = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene file to OUT.exr (+ OUT.png preview)");
  cmd->add_option("scene", o->scene_path, "Scene file: TOML (e.g. scenes/diffuse.toml) or glTF 2.0 (.gltf, .glb)")->required();
  cmd->add_option("-o,--output", o->output, "Output EXR (default: SCENE_STEM.exr here); .pfm for a raw film");
#ifdef CLPT_WITH_OIIO
  cmd->add_option("--exr-compression", o->exr_compression,
                  "The EXR's lossless compression: zip (default), zips, piz, rle or none (noisy films shrink by "
                  "5-8% under zip; none writes fastest)")
      ->check(CLI::IsMember(exr_compression_names()));
#endif
  cmd->add_option("--spp", o->spp, "Samples per pixel (default: the scene's)")->check(CLI::Range(int64_t(1), int64_t(1) << 31));
  cmd->add_option("--time", o->time_s, "Stop after this many seconds (with --spp: whichever comes first)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--target-error", o->target_error,
                  "Stop when clpt's estimate of the image's relative RMSE falls to this (e.g. 0.05 for 5%); "
                  "with --spp and --time, whichever comes first")
      ->check(CLI::Range(1e-4, 1.0));
  cmd->add_flag("--adaptive", o->adaptive,
                "Adaptive sampling: after 16 spp, half the samples go where the estimated error is largest "
                "(the other half stays uniform; the image stays unbiased)");
  cmd->add_option("--seed", o->seed, "Random seed (default: the scene's)");
  cmd->add_option("--device", o->device, "Device: index from `clpt devices`, cpu, gpu, cpu:N, gpu:N, a name substring; "
                  "several: all, or a comma list (0,1)");
  cmd->add_option("--width", o->width, "Image width in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", o->height, "Image height in pixels")->check(CLI::Range(1, 16384));
  cmd->add_option("--camera", o->camera,
                  "glTF scenes: the camera to render, by index into the file's cameras or by its (or its node's) "
                  "name (default: the first met in node order; docs/gltf.md)");
  cmd->add_option("--max-bounces", o->max_bounces, "Bounce rays after the camera ray (book: 9)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--sampler", o->sampler,
                  "jitter (stratified), grid (the book's 4x4 centres), sobol (Owen-scrambled Sobol points) or "
                  "sobol-grid (Sobol points, the camera's at the grid's centres: converges to grid's image at any spp)")
      ->check(CLI::IsMember(sampler_names()));
  cmd->add_option("--precision", o->precision,
                  "fast (float, fast maths), robust (float, IEEE; default) or double (fp64)")
      ->capture_default_str()
      ->check(CLI::IsMember({"fast", "robust", "double"}));
  cmd->add_option("--intersection", o->intersection,
                  "Ray/sphere formula: centre, surface or robust (default: the precision preset's)")
      ->check(CLI::IsMember({"centre", "surface", "robust"}));
  cmd->add_option("--estimator", o->estimator,
                  "book (no light sampling, the book's) or nee (next-event estimation + MIS); default: the scene's")
      ->check(CLI::IsMember({"book", "nee"}));
  cmd->add_option("--rr-from", o->rr_from, "Russian roulette from this bounce on (default: none)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--light-sampling", o->light_sampling,
                  "nee: sample the visible cap of each light (default) or the whole sphere")
      ->check(CLI::IsMember({"cap", "sphere"}));
  cmd->add_option("--environment", o->environment.file,
                  "Light the scene (TOML or glTF) with this equirectangular image (EXR, HDR, PNG, ...; replaces the "
                  "scene's [environment]; docs/environment.md), or 'none': no environment, and no default light for "
                  "a scene without lights");
  cmd->add_option("--environment-strength", o->environment.strength,
                  "Multiply the environment's radiance by S (default: the scene's, else 1)");
  cmd->add_option("--environment-rotation", o->environment.rotation_deg,
                  "Turn the environment DEG degrees about +Y (right-handed: 90 moves what was seen along +X to -Z)");
  cmd->add_option("--exposure", o->exposure_ev, "PNG preview: multiply the film by 2^EV first (the EXR stays linear)")
      ->check(CLI::Range(-64.0, 64.0));
  cmd->add_option("--tonemap", o->tonemap,
                  "PNG preview's tone curve: clamp (the book's, default) or aces (Narkowicz's ACES filmic fit); "
                  "then x^(1/2.2)")
      ->capture_default_str()
      ->check(CLI::IsMember({"clamp", "aces"}));
  cmd->add_flag("-q,--quiet", o->quiet, "Print nothing but errors");
  cmd->add_flag("--progress", o->progress, "Show the progress line even when stderr is not a terminal");
  cmd->add_flag("--explain", o->explain,
                "Print the render plan before rendering: per device the form, loop, kernel specialisation, "
                "work-group and path-pool sizes, launch sizing and memory");
  cmd->add_flag("--generic", o->generic, "Compile every feature in, not only what the scene uses");
  cmd->add_flag("--no-cache", o->no_cache, "Compile the kernel from source; neither read nor write "
                                           "clpt's kernel binary cache (`clpt cache dir`)");
  cmd->add_option("--form", o->form, "Execution form: auto (the device's default), megakernel or wavefront")
      ->check(CLI::IsMember({"auto", "megakernel", "wavefront"}));
  cmd->add_option("--megakernel-loop", o->megakernel_loop,
                  "Megakernel: auto (lockstep on CPUs, else per path), path or lockstep")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "path", "lockstep"}));
  cmd->add_option("--scene-loops", o->scene_loops,
                  "Specialised kernels' sphere and light loops: auto (unrolled on CPUs, rolled on GPUs), "
                  "unrolled or rolled")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "unrolled", "rolled"}));
  cmd->add_option("--cpu-vector-bits", o->cpu_vector_bits,
                  "PoCL x86 CPUs with AVX-512: vector width of the kernels, auto (512 there), 256 (LLVM's "
                  "choice) or 512 (16 work-items per vector iteration; README \"Speed\")")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "256", "512"}));
  cmd->add_option("--sphere-reads", o->sphere_reads,
                  "How shading reads the hit sphere: auto (selects on CPUs whose compiler has no fast gathers, with the robust and double presets), "
                  "indexed or selects (docs/performance.md, \"CPUs without fast gathers\")")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "indexed", "selects"}));
  cmd->add_option("--paths-in-flight", o->paths_in_flight, "Wavefront path slots (default: from the device)")
      ->check(CLI::Range(uint32_t(64), uint32_t(1) << 24));
  cmd->add_option("--local-size", o->local_size,
                  "Work-group size (default: the lockstep loop's 64, else the driver's choice)")
      ->check(CLI::Range(size_t(1), size_t(4096)));
  cmd->add_option("--launch-ms", o->launch_ms,
                  "Megakernel: size each launch to take about this many ms (GPU watchdogs); 0: one per pass")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 60000.0));
  cmd->add_option("--checkpoint", o->checkpoint, "Save the accumulated film to FILE periodically and at the end");
  cmd->add_option("--checkpoint-every", o->checkpoint_every_s, "Seconds between checkpoints")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  cmd->add_option("--resume", o->resume, "Continue the render saved in checkpoint FILE up to --spp");
#ifdef CLPT_WITH_OIIO
  cmd->add_option("--aovs", o->aovs,
                  "First-hit layers for denoisers (Open Image Denoise, OptiX) in the EXR: a comma list of albedo "
                  "(albedo.R/G/B), normal (N.X/Y/Z, world space) and depth (Z); docs/aovs.md");
#endif
  return [o] { return run(*o); };
}

}  // namespace clpt
