// `clpt kernels list`, `clpt kernels emit DIR --scene scenes/diffuse.toml` and `clpt kernels budget
// --scene scenes/diffuse.toml --device D` (tools/kernel_budget.h): the covering set of
// kernel variants (host/tools/kernel_variants.h), for the test tiers that check every variant on
// another OpenCL implementation (Oclgrind) and with GPU compilers (scripts/gpu_compile.sh).
// `emit` writes, per variant, the program's whole source (includes expanded, as clpt hands it
// to a driver) as NAME.cl and its build options as NAME.options, plus variants.txt listing the
// names in order, each file atomically.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "kernels/kernel_source.h"
#include "render/render_session.h"
#include "cl/cl_device.h"
#include "scene/scene_loader.h"
#include "tools/kernel_budget.h"
#include "tools/kernel_variants.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace clpt {
namespace {

struct KernelsOptions {
  std::string directory;
  std::string scene;
  std::string device = "gpu";
  std::string only;  // cold-builds: only the variants whose name contains this
};

int list_variants() {
  const auto variants = covering_kernel_variants();
  for (const KernelVariant& v : variants) std::printf("%s\n", v.name().c_str());
  std::fprintf(stderr, "%zu variants cover every value and every pair of values of %zu dimensions\n",
               variants.size(), kernel_variant_dimensions().size());
  return 0;
}

int emit_variants(const KernelsOptions& o) {
  check_output_directory("kernels emit", o.directory);
  const Scene diffuse = load_scene_file(o.scene);
  std::string names;
  for (const KernelVariant& v : covering_kernel_variants()) {
    const VariantProgram program = variant_program(variant_scene(diffuse, v), v);
    const std::string base = (std::filesystem::path(o.directory) / v.name()).string();
    write_file_atomically(base + ".cl", assemble_kernel_source(program.entry_file), "kernel source");
    write_file_atomically(base + ".options", kernel_build_options(program.features) + "\n", "build options");
    names += v.name() + " " + program.entry_file + "\n";
  }
  write_file_atomically((std::filesystem::path(o.directory) / "variants.txt").string(), names, "variant list");
  return 0;
}

int budget(const KernelsOptions& o) {
  const Scene diffuse = load_scene_file(o.scene);
  const DeviceInfo device = select_device(list_devices(), o.device);
  std::fprintf(stderr, "kernels budget: every covering variant built from source on %s, driver %s\n",
               device.label().c_str(), device.driver_version.c_str());
  const auto rows = measure_kernel_budget(
      device, diffuse, covering_kernel_variants(), [](const std::string& name) { std::fprintf(stderr, "  building %s\n", name.c_str()); },
      [](const std::string& log) { std::fprintf(stderr, "the first variant's build log:\n%s\n", log.c_str()); });
  std::fputs(kernel_budget_tsv(rows).c_str(), stdout);
  return 0;
}

// Every covering variant rendered once from source (a 32 x 24, 1-spp image of its scene, clpt's
// kernel cache unused and PoCL's turned off), printing its program build and first launch (where
// PoCL compiles the work-group functions): the cold build a user meets on first use of a feature
// combination (docs/performance.md, "Fixed costs"). A measurement, not a test: exit 0.
int cold_builds(const KernelsOptions& o) {
  std::vector<KernelVariant> variants;
  for (const KernelVariant& v : covering_kernel_variants())
    if (v.name().find(o.only) != std::string::npos) variants.push_back(v);
  if (variants.empty())
    throw Error(ExitCode::Usage, "kernels cold-builds: --only " + o.only + ": no variant's name contains it (clpt kernels list)");
  setenv("POCL_KERNEL_CACHE", "0", 1);  // before OpenCL is loaded: PoCL reads it once
  const Scene diffuse = load_scene_file(o.scene);
  double worst_specialised = 0, worst_generic = 0;
  for (const KernelVariant& v : variants) {
    RenderRequest request;
    request.use_kernel_cache = false;
    request.scene = diffuse;
    request.scene.settings.width = 32;
    request.scene.settings.height = 24;
    request.scene.settings.spp = 1;
    request.scene.settings.sampler = Sampler::Jitter;
    apply_variant(v, request);
    request.device = o.device;
    RenderReport report;
    run_render(request, report);
    const double seconds = report.build_seconds + report.first_launch_seconds;
    const bool generic = request.generic_kernel;
    (generic ? worst_generic : worst_specialised) = std::max(generic ? worst_generic : worst_specialised, seconds);
    std::printf("%6.2f s = build %5.2f + first launch %5.2f  %s\n", seconds, report.build_seconds,
                report.first_launch_seconds, v.name().c_str());
    std::fflush(stdout);
  }
  std::printf("slowest: specialised %.2f s, generic %.2f s (%s)\n", worst_specialised, worst_generic,
              select_device(list_devices(), o.device).label().c_str());
  return 0;
}

}  // namespace

std::function<int()> add_kernels_command(CLI::App& app) {
  auto o = std::make_shared<KernelsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "kernels", "The covering set of kernel variants: `list` their names, `emit` their sources and build options");
  cmd->require_subcommand(1);
  CLI::App* list = cmd->add_subcommand("list", "Print the variants' names, one a line");
  CLI::App* emit = cmd->add_subcommand(
      "emit", "Write NAME.cl (whole source) and NAME.options (build options) per variant, and variants.txt, into DIR");
  emit->add_option("dir", o->directory, "Existing output directory")->required();
  emit->add_option("--scene", o->scene, "The book's diffuse scene (scenes/diffuse.toml): variants change its balls")
      ->required();
  CLI::App* budget_cmd = cmd->add_subcommand(
      "budget", "Build every variant on a device and print, per kernel, what its driver reports: private and "
                "local memory, work-group limits, and (NVIDIA) ptxas's registers and spills, as TSV");
  budget_cmd->add_option("--scene", o->scene, "The book's diffuse scene (scenes/diffuse.toml)")->required();
  budget_cmd->add_option("--device", o->device, "The device, as for render --device")->capture_default_str();
  CLI::App* cold = cmd->add_subcommand(
      "cold-builds", "Render every variant once from source (no kernel cache; PoCL's turned off) and print its "
                     "program build plus first launch, seconds");
  cold->add_option("--scene", o->scene, "The book's diffuse scene (scenes/diffuse.toml)")->required();
  cold->add_option("--device", o->device, "The device, as for render --device")->capture_default_str();
  cold->add_option("--only", o->only, "Only the variants whose name contains this text (clpt kernels list)");
  return [o, list, emit, cold] {
    if (list->parsed()) return list_variants();
    if (emit->parsed()) return emit_variants(*o);
    if (cold->parsed()) return cold_builds(*o);
    return budget(*o);
  };
}

}  // namespace clpt
