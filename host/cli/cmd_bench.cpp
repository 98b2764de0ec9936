// `clpt bench`: the benchmark matrix (tools/bench.h), as a table and optionally JSON, with an
// optional comparison against a saved JSON baseline. Under an MPI launcher each row also reports
// its paths/s on the job's first 1 .. K ranks and the efficiency; rank 0 alone prints and writes.
#include <cstdio>
#include <memory>

#include "cli/commands.h"
#include "render/rank_group.h"
#include "util/atomic_file.h"
#include "tools/bench.h"
#include "util/error.h"

namespace clpt {
namespace {

struct BenchOptions {
  std::vector<std::string> scenes = {"scenes/diffuse.toml"};
  std::vector<std::string> forms = {"megakernel", "wavefront"};
  std::vector<std::string> loops = {"auto"};
  std::vector<std::string> kernels = {"specialised"};
  std::vector<std::string> precisions = {"robust"};
  std::vector<std::string> bvh_builders = {"clpt"};
  std::string sampler = "jitter";
  std::string cpu_vector_bits = "auto";
  std::string sphere_reads = "auto";
  std::string json, baseline, traversal_anchor, traversal_anchor_width = "auto";
  double tolerance = 10;
  bool no_vector_width = false, traversal_alone = false;
};

int run(BenchConfig config, const BenchOptions& o) {
  // Under an MPI launcher: the job's ranks (loads MPI); otherwise this process alone, a plain bench.
  RankGroup& ranks = process_rank_group();
  config.ranks = &ranks;
  for (const std::string& f : o.forms)
    config.forms.push_back(f == "wavefront" ? ExecutionForm::Wavefront : ExecutionForm::Megakernel);
  config.megakernel_loops.clear();
  for (const std::string& l : o.loops) config.megakernel_loops.push_back(*parse_megakernel_loop(l));
  config.generic.clear();
  for (const std::string& k : o.kernels) config.generic.push_back(k == "generic");
  config.scenes = o.scenes;
  config.sampler = sampler_from_name(o.sampler).value();  // CLI11 checked the name
  config.cpu_vector_bits = *parse_cpu_vector_bits(o.cpu_vector_bits);
  config.sphere_reads = *parse_sphere_reads(o.sphere_reads);
  config.precisions.clear();
  for (const std::string& p : o.precisions) config.precisions.push_back(*parse_precision(p));
  config.bvh_builders.clear();
  for (const std::string& b : o.bvh_builders) config.bvh_builders.push_back(parse_bvh_builder(b, "--bvh-builders"));
  if (ranks.size() > 1 && (config.bvh_builders.size() > 1 || config.bvh_builders.front() != BvhBuilder::Clpt))
    throw Error(ExitCode::Usage, "--bvh-builders: only clpt in an MPI job (its scaling renders as clpt render does)");
  if (config.devices.empty()) config.devices = {"best"};
  if (!o.json.empty() && ranks.coordinator()) check_output_file("--json", o.json);
  config.measure_vector_width = !o.no_vector_width;
  if (!o.traversal_anchor.empty()) check_traversal_anchor(o.traversal_anchor, "--traversal-anchor");
  config.traversal_anchor = o.traversal_anchor;
  if (o.traversal_anchor_width != "auto") {
    if (o.traversal_anchor.empty())
      throw Error(ExitCode::Usage, "--traversal-anchor-width: needs --traversal-anchor embree");
    config.traversal_anchor_width = std::stoi(o.traversal_anchor_width);  // CLI11 checked: 4 or 8
  }
  config.traversal_alone = o.traversal_alone || !o.traversal_anchor.empty();
  const std::vector<BenchRow> rows = run_bench(config, ranks.coordinator());
  if (!ranks.coordinator()) return 0;  // rank 0 prints, writes and compares
  std::printf("%s", bench_table(rows).c_str());
  if (!o.json.empty()) write_file_atomically(o.json, bench_json(rows, config), "--json");
  if (o.baseline.empty()) return 0;
  const std::vector<std::string> regressions = bench_regressions(rows, o.baseline, o.tolerance);
  for (const std::string& r : regressions) std::printf("REGRESSION %s\n", r.c_str());
  if (regressions.empty()) std::printf("no figure fell more than %.1f%% below %s\n", o.tolerance, o.baseline.c_str());
  return regressions.empty() ? 0 : static_cast<int>(ExitCode::Failure);
}

}  // namespace

std::function<int()> add_bench_command(CLI::App& app) {
  auto config = std::make_shared<BenchConfig>();
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Benchmark scene x form (x megakernel loop) x kernel x precision x estimator x device x work-group size");
  cmd->add_option("--scenes", o->scenes, "Scene files, TOML or glTF (default: scenes/diffuse.toml)")->delimiter(',');
  cmd->add_option("--forms", o->forms, "megakernel,wavefront")
      ->delimiter(',')->check(CLI::IsMember({"megakernel", "wavefront"}));
  cmd->add_option("--megakernel-loops", o->loops, "auto,path,lockstep (default: auto: lockstep on CPUs, else path)")
      ->delimiter(',')->check(CLI::IsMember({"auto", "path", "lockstep"}));
  cmd->add_option("--kernels", o->kernels, "specialised,generic")
      ->delimiter(',')->check(CLI::IsMember({"specialised", "generic"}));
  cmd->add_option("--precisions", o->precisions, "fast,robust,double (default: robust)")
      ->delimiter(',')->check(CLI::IsMember({"fast", "robust", "double"}));
  cmd->add_option("--estimators", config->estimators, "book,nee (default: the scene's)")
      ->delimiter(',')->check(CLI::IsMember({"book", "nee"}));
  cmd->add_option("--devices", config->devices, "Device specs as for render --device, or all (default: best)")
      ->delimiter(',');
  cmd->add_option("--local-sizes", config->local_sizes, "Work-group sizes, 0 = the form's default")
      ->delimiter(',')->check(CLI::Range(size_t(0), size_t(4096)));
  cmd->add_option("--width", config->width, "Image width")->check(CLI::Range(1, 16384));
  cmd->add_option("--height", config->height, "Image height")->check(CLI::Range(1, 16384));
  cmd->add_option("--spp", config->spp, "Samples per pixel of one timed run")->check(CLI::Range(1u, 65536u));
  cmd->add_option("--warmup", config->warmup, "Untimed runs first")->check(CLI::Range(0, 100));
  cmd->add_option("--repeat", config->repeat, "Timed runs")->check(CLI::Range(1, 1000));
  cmd->add_option("--paths-in-flight", config->paths_in_flight, "Wavefront path slots (0: the device's default)");
  cmd->add_option("--cpu-vector-bits", o->cpu_vector_bits,
                  "As for render: auto, 256 or 512 (PoCL x86 CPUs with AVX-512), for every row; the rows built "
                  "512 bits wide say so")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "256", "512"}));
  cmd->add_option("--sphere-reads", o->sphere_reads, "As for render: auto, indexed or selects, for every row")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "indexed", "selects"}));
  cmd->add_option("--sampler", o->sampler,
                  "Sampler of every run (default jitter; the rows do not name it, so compare a --baseline "
                  "taken with the same one)")
      ->check(CLI::IsMember(sampler_names()));
  cmd->add_option("--bvh-builders", o->bvh_builders,
                  "Hierarchy builders: clpt (the default, what renders use), clpt-1thread (the same hierarchy "
                  "built on one thread), embree, embree-1thread (only in a build with Embree; "
                  "docs/performance.md \"Traversal\")")
      ->delimiter(',');
  cmd->add_option("--traversal-anchor", o->traversal_anchor,
                  "embree: every row with triangles, or spheres in a hierarchy, also times Embree's rtcIntersect1 "
                  "and rtcIntersect16 on the same primitives and rays as its traversal statistics (only in a build with Embree; "
                  "docs/performance.md \"Traversal\"); implies --traversal-alone");
  cmd->add_option("--traversal-anchor-width", o->traversal_anchor_width,
                  "auto (Embree's choice: 8 on AVX machines), 4 or 8: the width of the tree of the anchor's "
                  "fastest scene over triangles (Embree's tri_accel bvh4.triangle4 or bvh8.triangle4), e.g. 4 "
                  "to time Embree at clpt's width; the robust scene stays as Cycles builds it")
      ->check(CLI::IsMember({"auto", "4", "8"}))
      ->capture_default_str();
  cmd->add_flag("--traversal-alone", o->traversal_alone,
                "Every row with triangles, or spheres in a hierarchy, also times clpt's closest-hit queries alone (kernels/trace.cl with the "
                "row's options, no shading) on the rays of its traversal statistics: rays/s, per CPU-second, hits");
  cmd->add_flag("--no-vector-width", o->no_vector_width,
                "Do not measure each row's vector width (one extra small cold compile per row; the lanes "
                "column and the JSON's vector_width then say not measured)");
  cmd->add_option("--json", o->json, "Also write the results as JSON");
  cmd->add_option("--baseline", o->baseline, "Compare with a saved --json file; exit 1 on a regression");
  cmd->add_option("--tolerance", o->tolerance, "Allowed drop of median paths/s against --baseline, percent")
      ->check(CLI::Range(0.0, 100.0));
  return [config, o] { return run(*config, *o); };
}

}  // namespace clpt
