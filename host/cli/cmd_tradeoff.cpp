// `clpt tradeoff SCENE --reference REF.exr`: speed against accuracy. Renders the scene for a series
// of time budgets in every chosen combination of precision, estimator, execution form, sampler,
// adaptive sampling and device, measures each render's error against the reference and splits it into noise and bias
// (tools/tradeoff.h), then prints how long each combination takes to reach given RMSEs and writes
// the runs as CSV or JSON and an RMSE-versus-time plot (through gnuplot).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>

#include "cl/cl_device.h"
#include "cli/commands.h"
#include "io/image_io.h"
#include "io/render_file.h"
#include "kernels/kernel_options.h"
#include "render/limits.h"
#include "render/render_session.h"
#include "render/form_rule.h"
#include "scene/scene_loader.h"
#include "tools/gnuplot.h"
#include "tools/tradeoff.h"
#include "tools/tradeoff_output.h"
#include "util/atomic_file.h"
#include "util/error.h"
#include "util/interrupt.h"

namespace clpt {
namespace {

struct TradeoffOptions {
  std::string scene_path, reference_path;
  std::vector<std::string> precisions = {"robust"};
  std::vector<std::string> estimators = {"book"};
  std::vector<std::string> forms = {"auto"};
  std::vector<std::string> devices = {""};  // "" = the default device
  std::vector<double> budgets;              // --budgets; empty: --min-time/--max-time/--steps or the default
  std::optional<double> min_time_s, max_time_s;
  int steps = 4;
  std::vector<double> target_rmse;
  std::string target_from;
  std::string output, plot;
  std::optional<int> width, height, max_bounces, rr_from;
  std::vector<std::string> samplers;  // --sampler: one sets the scene's; several are a dimension
  std::vector<std::string> adaptive = {"off"};  // --adaptive: off, on, or both (a dimension)
  std::optional<uint64_t> seed;
  double launch_ms = 75;  // megakernel launch target, as `clpt render --launch-ms`
  bool no_warmup = false;
  bool quiet = false;
};

const std::vector<double> kDefaultBudgets = {0.25, 0.5, 1, 2};

// Returns the gnuplot to use for --plot ("" without --plot).
std::string check_outputs(const TradeoffOptions& o) {
  if (!o.output.empty()) {
    const std::string ext = std::filesystem::path(o.output).extension().string();
    if (ext != ".csv" && ext != ".json")
      throw Error(ExitCode::Usage, "-o " + o.output + ": the output must be a .csv or a .json file");
    check_output_file("-o", o.output);
  }
  if (o.plot.empty()) return "";
  if (std::filesystem::path(o.plot).extension() != ".png")
    throw Error(ExitCode::Usage, "--plot " + o.plot + ": the plot must be a .png file");
  check_output_file("--plot", o.plot);
  const std::string gnuplot = find_gnuplot();
  if (gnuplot.empty())
    throw Error(ExitCode::Usage, "--plot " + o.plot + ": gnuplot is not on PATH; clpt draws its plots with it "
                                 "(Debian: apt-get install gnuplot-nox), or leave out --plot");
  return gnuplot;
}

std::vector<double> budgets_from(const TradeoffOptions& o) {
  if (!o.budgets.empty()) {
    std::vector<double> b = o.budgets;
    std::sort(b.begin(), b.end());
    b.erase(std::unique(b.begin(), b.end()), b.end());
    return b;
  }
  if (!o.min_time_s && !o.max_time_s) return kDefaultBudgets;
  if (!o.min_time_s || !o.max_time_s)
    throw Error(ExitCode::Usage, "--min-time and --max-time go together (or give --budgets)");
  try {
    return geometric_budgets(*o.min_time_s, *o.max_time_s, o.steps);
  } catch (const std::invalid_argument& e) {
    throw Error(ExitCode::Usage, "--min-time/--max-time/--steps: " + std::string(e.what()));
  }
}

// The reference (io/render_file.h) as the error measures read it.
struct LoadedReference {
  MeanVarianceImage image;
  TradeoffReference info;
  RenderFileInfo file;
};

// Its size must be the renders'.
LoadedReference load_reference(const std::string& path, RenderFile file, int width, int height) {
  if (file.image.width != width || file.image.height != height)
    throw Error(ExitCode::Usage, "--reference " + path + " is " + std::to_string(file.image.width) + "x" +
                                     std::to_string(file.image.height) + " but the renders are " +
                                     std::to_string(width) + "x" + std::to_string(height) +
                                     ": they must be the same size (set --width and --height)");
  LoadedReference ref;
  ref.image = std::move(file.image);
  ref.info = {path, width, height, file.info.spp, noise_rms(ref.image)};
  ref.file = std::move(file.info);
  return ref;
}

// A reference made from another scene file or path length measures a different image: say so.
// `samplers`: the renders' samplers (--sampler, or the scene's when none or one is given).
void warn_about_mismatches(const LoadedReference& ref, const Scene& scene, const std::vector<std::string>& samplers) {
  if (!ref.file.scene_hash.empty() && ref.file.scene_hash != scene.file_hash)
    std::fprintf(stderr, "clpt: warning: --reference %s was rendered from another scene file (clpt:scene_hash %s, "
                         "%s has %s): its bias figures compare different images\n",
                 ref.info.path.c_str(), ref.file.scene_hash.c_str(), scene.file.c_str(), scene.file_hash.c_str());
  auto filter = [](const std::string& sampler) {
    const std::optional<Sampler> known = sampler_from_name(sampler);
    return std::string(known ? pixel_filter_name(*known) : "unknown");
  };
  for (const std::string& sampler : samplers)
    if (!ref.file.sampler.empty() && filter(ref.file.sampler) != filter(sampler))
      std::fprintf(stderr, "clpt: warning: --reference %s used the %s sampler but renders use %s: the two "
                           "converge to different pixel filters, which shows as bias (set --sampler)\n",
                   ref.info.path.c_str(), ref.file.sampler.c_str(), sampler.c_str());
  const std::optional<uint64_t> bounces = ref.file.max_bounces;
  if (bounces && *bounces != uint64_t(scene.settings.max_bounces))
    std::fprintf(stderr, "clpt: warning: --reference %s has max_bounces %llu but the renders %d: the "
                         "truncation differs, which shows as bias\n",
                 ref.info.path.c_str(), (unsigned long long)*bounces, scene.settings.max_bounces);
}

// Random numbers are addressed by (seed, pixel, sample): renders with the reference's seed would
// repeat its first samples and look closer to it than they are. An explicit --seed equal to the
// reference's is an error; the scene's own seed moves on by one.
uint64_t choose_seed(const TradeoffOptions& o, const Scene& scene, const LoadedReference& ref, bool& moved) {
  const std::optional<uint64_t> ref_seed = ref.file.seed;
  moved = false;
  if (o.seed) {
    if (ref_seed && *o.seed == *ref_seed)
      throw Error(ExitCode::Usage, "--seed " + std::to_string(*o.seed) + ": the reference " + ref.info.path +
                                       " was rendered with this seed; the renders would share its random "
                                       "numbers. Pick another --seed");
    return *o.seed;
  }
  if (ref_seed && scene.settings.seed == *ref_seed) {
    moved = true;
    return *ref_seed + 1;
  }
  return scene.settings.seed;
}

// Every combination, precision outermost and device innermost; forms named "auto" become the
// device's default. Combinations that come out the same are kept once.
std::vector<Combination> resolve_combinations(const TradeoffOptions& o, const Scene& scene) {
  const std::vector<DeviceInfo> all = list_devices();
  std::vector<Combination> out;
  std::set<std::string> seen;
  for (const std::string& p : o.precisions)
    for (const std::string& e : o.estimators)
      for (const std::string& f : o.forms)
        for (const std::string& sampler : o.samplers.size() > 1 ? o.samplers : std::vector<std::string>{""})
        for (const std::string& adaptive : o.adaptive)
        for (const std::string& spec : o.devices) {
          const DeviceInfo& device = select_device(all, spec);
          Combination c;
          c.precision = *parse_precision(p);
          c.estimator = *parse_estimator(e);
          c.form = f == "auto" ? default_form_for(device, features_for_scene(scene)).form
                               : f == "wavefront" ? ExecutionForm::Wavefront : ExecutionForm::Megakernel;
          c.sampler = sampler;
          c.adaptive = adaptive == "on";
          c.device_spec = spec;
          c.device_index = device.index;
          c.device_name = device.name;
          if (seen.insert(c.label()).second) out.push_back(c);
        }
  return out;
}

// One fresh render of the combination: for budget_s seconds, or fixed_spp samples when non-zero.
// Sets `interrupted` when SIGINT/SIGTERM stopped it early (its figures are then not a run).
TradeoffRun render_run(const Scene& scene, const Combination& c, double budget_s, uint64_t fixed_spp,
                       double launch_target_s, const MeanVarianceImage& reference, bool& interrupted) {
  RenderRequest request;
  request.launch_target_s = launch_target_s;
  request.scene = scene;
  request.scene.settings.estimator = estimator_name(c.estimator);
  if (!c.sampler.empty()) request.scene.settings.sampler = sampler_from_name(c.sampler).value();  // checked
  request.device = std::to_string(c.device_index);  // resolved once: the same device every run
  request.precision = c.precision;
  request.form = c.form;
  request.adaptive = c.adaptive;
  if (fixed_spp > 0) {
    request.scene.settings.spp = int64_t(fixed_spp);
    request.spp_given = true;
  } else {
    request.time_limit_s = budget_s;
    request.spp_given = false;
  }
  request.interrupt = &interrupt_flag();
  RenderReport report;
  const Film film = run_render(request, report);
  interrupted = report.interrupted || interrupt_flag().load();
  TradeoffRun run;
  run.combination = c;
  run.budget_s = fixed_spp > 0 ? 0 : budget_s;
  run.fixed_spp = fixed_spp;
  run.render_s = report.render_seconds;
  run.build_s = report.build_seconds;
  run.spp = report.spp;
  run.paths = report.paths;
  run.dropped = report.dropped;
  if (film.samples_per_pixel() > 0)
    run.error = split_error(film.mean_variance(), reference);
  return run;
}

// The smallest sample count the scene's sampler takes (the grid sampler works in 4x4 cells).
uint64_t sampler_granularity(const Scene& scene) { return scene.settings.sampler == Sampler::Grid ? 16 : 1; }
// The same for a combination, whose sampler may be its own (--sampler with several).
uint64_t sampler_granularity(const Scene& scene, const Combination& c) {
  return c.sampler.empty() ? sampler_granularity(scene) : c.sampler == "grid" ? 16 : 1;
}

void apply_overrides(const TradeoffOptions& o, Scene& scene) {
  RenderSettings& s = scene.settings;
  if (o.width) s.width = *o.width;
  if (o.height) s.height = *o.height;
  if (o.max_bounces) s.max_bounces = *o.max_bounces;
  if (o.rr_from) s.rr_from = *o.rr_from;
  if (o.samplers.size() == 1) s.sampler = sampler_from_name(o.samplers.front()).value();  // CLI11 checked it
  s.spp = int64_t(sampler_granularity(scene));  // budget runs are bounded by time, not by this
  check_scene_limits(scene, {o.width || o.height, false, o.max_bounces.has_value()});
}

std::vector<ErrorTarget> error_targets(const TradeoffOptions& o, const TradeoffResult& result,
                                       const std::optional<TradeoffRun>& target_run) {
  std::vector<ErrorTarget> targets;
  for (double e : o.target_rmse) targets.push_back({e, "--target-rmse"});
  if (target_run)
    targets.push_back({target_run->error.rmse, target_run->combination.label() + " at " +
                                                   std::to_string(target_run->fixed_spp) + " spp (--target-from)"});
  if (!targets.empty() || result.runs.empty()) return targets;
  const TradeoffRun& first = result.runs.front();  // the first combination at its smallest budget
  char budget[32];
  std::snprintf(budget, sizeof budget, "%g", first.budget_s);
  return {{first.error.rmse, first.combination.label() + " at its smallest budget (" + budget + " s)"}};
}

std::optional<TargetFrom> target_from_option(const std::string& text) {
  if (text.empty()) return std::nullopt;
  try {
    return parse_target_from(text);
  } catch (const std::invalid_argument& e) {
    throw Error(ExitCode::Usage, "--target-from " + text + ": " + e.what());
  }
}

void write_outputs(const TradeoffOptions& o, const TradeoffResult& result, const std::string& gnuplot) {
  if (!o.output.empty()) {
    const bool json = std::filesystem::path(o.output).extension() == ".json";
    write_file_atomically(o.output, json ? tradeoff_json(result) : tradeoff_csv(result.runs), "-o");
    if (!o.quiet) std::printf("wrote %s\n", o.output.c_str());
  }
  if (!o.plot.empty()) {
    write_gnuplot_png(gnuplot, "--plot", o.plot,
                      [&](const std::string& tmp) { return gnuplot_script(result, tmp); });
    if (!o.quiet) std::printf("wrote %s\n", o.plot.c_str());
  }
}

int run(const TradeoffOptions& o) {
  // Everything that can be wrong with the command line is checked before the first render.
  const std::string gnuplot = check_outputs(o);
  const std::vector<double> budgets = budgets_from(o);
  const std::optional<TargetFrom> target_from = target_from_option(o.target_from);
  Scene scene = load_scene_file(o.scene_path);
  RenderFile reference_file = read_render_file(o.reference_path, "--reference " + o.reference_path);
  if (!o.width && !o.height) {  // the renders take the reference's size unless told otherwise
    scene.settings.width = reference_file.image.width;
    scene.settings.height = reference_file.image.height;
  }
  apply_overrides(o, scene);
  // --target-from renders with the first combination's sampler.
  const bool target_sampler_is_grid = o.samplers.size() > 1 ? o.samplers.front() == "grid"
                                                            : scene.settings.sampler == Sampler::Grid;
  if (target_from && target_sampler_is_grid && target_from->spp % 16 != 0)
    throw Error(ExitCode::Usage, "--target-from " + o.target_from + ": the grid sampler needs a "
                                 "multiple of 16 samples per pixel");
  const LoadedReference ref =
      load_reference(o.reference_path, std::move(reference_file), scene.settings.width, scene.settings.height);
  warn_about_mismatches(ref, scene, o.samplers.size() > 1 ? o.samplers
                                                          : std::vector<std::string>{sampler_name(scene.settings.sampler)});
  bool seed_moved = false;
  scene.settings.seed = choose_seed(o, scene, ref, seed_moved);
  TradeoffResult result;
  result.scene = scene.file;
  result.seed = scene.settings.seed;
  result.reference = ref.info;
  result.combinations = resolve_combinations(o, scene);

  if (!o.quiet) {
    std::printf("reference %s: %dx%d, %s spp, noise RMS %.4g (RMS standard error of its pixel means)\n",
                ref.info.path.c_str(), ref.info.width, ref.info.height,
                ref.info.spp ? std::to_string(*ref.info.spp).c_str() : "unknown", ref.info.noise_rms);
    std::printf("rendering %s at %dx%d, seed %llu%s: %zu combination(s) x %zu budget(s)\n", scene.file.c_str(),
                scene.settings.width, scene.settings.height, (unsigned long long)scene.settings.seed,
                seed_moved ? " (the reference's seed + 1)" : "", result.combinations.size(), budgets.size());
  }
  install_interrupt_handlers();
  const double launch_s = o.launch_ms / 1000;
  bool interrupted = false;
  std::set<std::string> warmed;
  // An untimed render of a few samples first: kernel build and PoCL's first-launch compile would
  // otherwise land in the first budget's time.
  auto warm_up = [&](const Combination& c) {
    if (o.no_warmup || !warmed.insert(c.label()).second) return;
    render_run(scene, c, 0, sampler_granularity(scene, c), launch_s, ref.image, interrupted);
  };
  for (const Combination& c : result.combinations) {
    warm_up(c);
    for (size_t b = 0; b < budgets.size() && !interrupted; ++b) {
      const TradeoffRun run = render_run(scene, c, budgets[b], 0, launch_s, ref.image, interrupted);
      if (interrupted) break;
      result.runs.push_back(run);
      if (!o.quiet) std::printf("%s", run_summary_line(run).c_str());
      std::fflush(stdout);
    }
    if (interrupted) break;
  }
  std::optional<TradeoffRun> target_run;
  if (target_from && !interrupted && !result.combinations.empty()) {
    const Combination c = target_from->applied_to(result.combinations.front());
    warm_up(c);
    const TradeoffRun run = render_run(scene, c, 0, target_from->spp, launch_s, ref.image, interrupted);
    if (!interrupted) {
      target_run = run;
      result.runs.push_back(run);
      if (!o.quiet) std::printf("%s", run_summary_line(run).c_str());
    }
  }
  result.targets = error_targets(o, result, target_run);
  std::printf("%s", time_to_error_table(result).c_str());
  write_outputs(o, result, gnuplot);
  if (!interrupted) return 0;
  std::fprintf(stderr, "clpt: interrupted: wrote the %zu finished run(s)\n", result.runs.size());
  return static_cast<int>(ExitCode::Interrupted);
}

}  // namespace

std::function<int()> add_tradeoff_command(CLI::App& app) {
  auto o = std::make_shared<TradeoffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tradeoff",
      "Speed against accuracy: RMSE against a reference, split into noise and bias, versus render time, "
      "for each combination of precision x estimator x form x sampler x adaptive x device");
  cmd->add_option("scene", o->scene_path, "Scene file: TOML or glTF 2.0 (.gltf, .glb)")->required();
  cmd->add_option("--reference", o->reference_path,
                  "Converged EXR with variance channels, e.g. from `clpt render --precision double --spp 4096`; "
                  "the same size as the renders")
      ->required();
  cmd->add_option("--precision", o->precisions, "Precisions to compare: fast,robust,double (default robust)")
      ->delimiter(',')->check(CLI::IsMember({"fast", "robust", "double"}));
  cmd->add_option("--estimator", o->estimators, "Estimators to compare: book,nee (default book)")
      ->delimiter(',')->check(CLI::IsMember({"book", "nee"}));
  cmd->add_option("--form", o->forms, "Execution forms: auto,megakernel,wavefront (default auto: the device's)")
      ->delimiter(',')->check(CLI::IsMember({"auto", "megakernel", "wavefront"}));
  cmd->add_option("--device", o->devices, "Devices, each as for `clpt render --device` (default: the best)")
      ->delimiter(',');
  auto* budgets = cmd->add_option("--budgets", o->budgets, "Time budgets in seconds (default 0.25,0.5,1,2)")
                      ->delimiter(',')->check(CLI::PositiveNumber);
  cmd->add_option("--min-time", o->min_time_s, "Smallest budget, seconds (with --max-time, --steps)")
      ->check(CLI::PositiveNumber)->excludes(budgets);
  cmd->add_option("--max-time", o->max_time_s, "Largest budget, seconds")->check(CLI::PositiveNumber)->excludes(budgets);
  cmd->add_option("--steps", o->steps, "Budgets from --min-time to --max-time, in geometric progression")
      ->capture_default_str()->check(CLI::Range(1, 64))->excludes(budgets);
  cmd->add_option("--target-rmse", o->target_rmse, "RMSEs for the time-to-reach table")
      ->delimiter(',')->check(CLI::PositiveNumber);
  cmd->add_option("--target-from", o->target_from,
                  "A target RMSE measured by one extra render: [PRECISION/][ESTIMATOR/][FORM/]@SPP, e.g. book@256 "
                  "(unnamed parts from the first combination). Default target, without this or --target-rmse: "
                  "the first combination's RMSE at its smallest budget");
  cmd->add_option("-o,--output", o->output, "Write every run to FILE.csv (header row) or FILE.json");
  cmd->add_option("--plot", o->plot, "Draw log RMSE against log time, one curve per combination, to FILE.png "
                                     "(needs gnuplot)");
  cmd->add_option("--width", o->width, "Image width in pixels (default: the reference's)")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", o->height, "Image height in pixels (default: the reference's)")->check(CLI::Range(1, 16384));
  cmd->add_option("--max-bounces", o->max_bounces, "Bounce rays after the camera ray (book: 9)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--rr-from", o->rr_from, "Russian roulette from this bounce on (default: the scene's, none)")
      ->check(CLI::Range(0, 1000));
  cmd->add_option("--sampler", o->samplers,
                  "jitter, grid or sobol (default: the scene's; the reference's, for no bias); several, "
                  "e.g. jitter,sobol: compared as a dimension (jitter and sobol converge to one image, grid to another)")
      ->delimiter(',')->check(CLI::IsMember(sampler_names()));
  cmd->add_option("--adaptive", o->adaptive,
                  "Adaptive sampling (`clpt render --adaptive`): off (default), on, or off,on to compare both as a dimension")
      ->delimiter(',')->check(CLI::IsMember({"off", "on"}));
  cmd->add_option("--seed", o->seed, "Random seed (default: the scene's; never the reference's)");
  cmd->add_option("--launch-ms", o->launch_ms,
                  "Megakernel launch size target in ms, as for `clpt render --launch-ms` (0: one launch per pass)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 60000.0));
  cmd->add_flag("--no-warmup", o->no_warmup, "Skip the untimed render of each combination before its budgets");
  cmd->add_flag("-q,--quiet", o->quiet, "Print only the time-to-reach table and errors");
  cmd->footer("Relative MSE is the mean over pixels and channels of (x - ref)^2 / (ref^2 + 1e-2). Noise is the mean of "
              "the render's and the reference's variance of the pixel mean; bias^2 = max(0, MSE - noise).");
  return [o] { return run(*o); };
}

}  // namespace clpt
