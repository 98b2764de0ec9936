// `clpt bench`: a matrix of scene x execution form (and the megakernel's loop) x kernel
// (specialised or generic) x precision preset x estimator x device x work-group size, each with cold and cached kernel build times, warm-up and repeated timed
// passes (median and spread of paths/s and ray segments/s), and per-stage device time of the
// wavefront from OpenCL profiling events. The same renderers as `clpt render`, nothing else.
// In an MPI job (`mpirun -n K clpt bench`, docs/mpi.md) each row is also rendered as `clpt render`
// renders over ranks, on the job's first 1, 2, .. K ranks: paths/s and efficiency per rank count.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "kernels/kernel_options.h"
#include "render/renderer.h"
#include "scene/bvh_builders.h"
#include "scene/scene.h"
#include "tools/traversal_anchor.h"
#include "tools/traversal_trace.h"
#include "tools/vector_width.h"

namespace clpt {

class RankGroup;

struct BenchConfig {
  std::vector<std::string> scenes;             // scene files
  std::vector<ExecutionForm> forms;
  std::vector<MegakernelLoop> megakernel_loops = {MegakernelLoop::Auto};  // megakernel rows only
  std::vector<std::string> devices;            // --device values; "all" expands to every device
  std::vector<size_t> local_sizes = {0};       // 0: the form's default
  std::vector<bool> generic = {false};         // false: specialised kernel, true: generic
  std::vector<Precision> precisions = {Precision::Robust};
  std::vector<std::string> estimators = {""};  // "book", "nee"; "": the scene's
  int width = 320, height = 240;
  uint32_t spp = 16;                           // samples per pixel of one timed run
  int warmup = 1, repeat = 5;
  uint32_t paths_in_flight = 0;                // wavefront; 0: the device's default
  Sampler sampler = Sampler::Jitter;           // one for the whole matrix (rows do not name it)
  // One for the whole matrix (--cpu-vector-bits); rows record the width they were built for.
  CpuVectorBits cpu_vector_bits = CpuVectorBits::Auto;
  SphereReads sphere_reads = SphereReads::Auto;  // --sphere-reads, for the whole matrix
  // Who builds the hierarchy of each row's device scene (a plain bench only: the MPI scaling
  // renders as `clpt render` does, with clpt's own builder).
  std::vector<BvhBuilder> bvh_builders = {BvhBuilder::Clpt};
  // The ranks of an MPI job; null or a group of one: a plain bench. A larger group: every rank
  // calls run_bench with the same config and must resolve the same matrix (as many --devices,
  // the same fp64 support); rank 0 times each row alone, the others idle, then the row's render
  // runs on the first 1 .. K ranks (BenchRow::ranks).
  RankGroup* ranks = nullptr;
  // Measure each row's vector width (tools/vector_width.h): one extra cold compile per row in a
  // child process. Only where this process is the clpt executable (the probe reruns it).
  bool measure_vector_width = false;
  // --traversal-anchor: "" (none) or "embree": every row with triangles or hierarchy spheres also
  // times Embree's closest-hit queries on them and the statistics' rays (tools/traversal_anchor.h).
  std::string traversal_anchor;
  // --traversal-anchor-width: 0 (Embree's choice), 4 or 8: the width of the anchor's fastest
  // scene's tree over triangles (AnchorRates::tri_accel).
  int traversal_anchor_width = 0;
  // --traversal-alone (and --traversal-anchor): every row with triangles or hierarchy spheres also
  // times clpt's own closest-hit queries on the statistics' rays (kernels/trace.cl;
  // tools/traversal_trace.h).
  bool traversal_alone = false;
};

struct Spread {
  double median = 0, min = 0, max = 0;
};

// A row's render on the first `ranks` ranks of an MPI job: run_render over that sub-group (its
// paths over the wall time of its passes, as the render summary's combined rate; kernel builds and
// start-up excluded), warm-up and repeat as the row's; efficiency = median paths/s at `ranks`
// over `ranks` times the median at 1 rank.
struct RankRate {
  int ranks = 1;
  Spread paths_per_s;
  double efficiency = 1;
};

struct BenchRow {
  std::string scene, form, kernel, precision, estimator, device;
  std::string loop;       // the megakernel's loop as run ("lockstep", "path"); "" for the wavefront
  size_t local_size = 0;  // the work-group size as run; 0: the driver's choice
  // The kernels' CPU vector width as built: "512" (16 lanes set on PoCL's vectoriser), else "default".
  std::string cpu_vector_bits = "default";
  std::string sphere_reads = "indexed";  // "selects" where the kernel read the hit sphere by selects
  uint32_t paths_in_flight = 0;
  double build_cold_s = 0, build_cached_s = 0;
  // The bounding volume hierarchy (none: nodes 0): what it holds, its host build time and the
  // device bytes its triangles take (GpuTriangle + GpuTriangleShading + the nodes, per triangle).
  std::string bvh_builder = "clpt";  // bvh_builder_name()
  uint64_t triangles = 0, hierarchy_spheres = 0, bvh_nodes = 0;
  int bvh_depth = 0;       // 4-wide nodes on the longest path (Bvh::depth)
  int bvh_stack_need = 0;  // the deepest traversal stack the tree can need (Bvh::stack_need)
  double bvh_build_s = 0;
  double device_bytes_per_triangle = 0;
  int bvh_build_threads = 1;
  double bvh_build_cpu_s = 0;  // CPU seconds of the build, all threads (Bvh::build_cpu_seconds)
  // The hierarchy's statistics (scene/bvh_stats.h): its SAH cost, and per closest-hit ray of the
  // replica's sample (stats_rays at the row's image size: camera rays, then one diffuse bounce
  // from each camera hit) the nodes visited, box tests, triangle tests and hierarchy sphere tests,
  // and the triangle loop's tests where the row's kernel has one beside the hierarchy.
  double sah_cost = 0;
  uint64_t stats_rays = 0, stats_camera_rays = 0;
  double nodes_per_ray = 0, boxes_per_ray = 0, triangles_per_ray = 0, spheres_per_ray = 0, loop_triangles_per_ray = 0;
  Spread paths_per_s, segments_per_s;
  // clpt's closest-hit rays/s: its segments/s (every segment of a path is one closest-hit query;
  // shading, shadow rays and the loop's spheres share the time), the figure set beside the anchor's.
  std::optional<AnchorRates> anchor;  // --traversal-anchor, rows with triangles
  // --traversal-alone or --traversal-anchor, rows with triangles: clpt's own closest-hit queries on
  // the statistics' rays and the row's triangles (kernels/trace.cl with the row's kernel options;
  // tools/traversal_trace.h).
  std::optional<TraceRates> trace;
  // Paths per CPU-second of this process (process_cpu_seconds over each timed pass): on a CPU
  // device the figure that holds while other work shares the cores; on a GPU, host time only.
  Spread paths_per_cpu_s;
  std::vector<std::pair<std::string, double>> stage_seconds;  // median per run, wavefront only
  std::vector<RankRate> ranks;  // an MPI job, at rank 0: 1 .. K ranks; else empty
  std::optional<VectorWidthReport> vector_width;  // unset: not measured (--no-vector-width)
  // Identifies the row across runs (for --baseline); names a builder other than clpt and a
  // vector width other than the default.
  std::string key() const;
};

// In an MPI job the rows are rank 0's (the other ranks' rows hold no figures); collective.
std::vector<BenchRow> run_bench(const BenchConfig& config, bool show_progress);

std::string bench_table(const std::vector<BenchRow>& rows);
std::string bench_json(const std::vector<BenchRow>& rows, const BenchConfig& config);

// Rows of `baseline_json` (a file written by --json) whose median paths/s the new rows fall below
// by more than tolerance_percent; one line each. Throws Error(Usage) for an unreadable file.
std::vector<std::string> bench_regressions(const std::vector<BenchRow>& rows,
                                           const std::string& baseline_path,
                                           double tolerance_percent);

}  // namespace clpt
