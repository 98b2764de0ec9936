#include "tools/bench.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <thread>

#include "cl/cl_context.h"
#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "render/film.h"
#include "render/device_pool.h"
#include "render/rank_group.h"
#include "render/render_plan.h"
#include "render/render_session.h"
#include "scene/bvh_stats.h"
#include "scene/device_scene.h"
#include "scene/scene_loader.h"
#include "util/byte_buffer.h"
#include "util/error.h"
#include "util/clock.h"

namespace clpt {
namespace {

Spread spread_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  Spread s;
  s.min = v.front();
  s.max = v.back();
  s.median = v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
  return s;
}

// --devices entries resolve as render's --device does ("all": every real device).
std::vector<DeviceInfo> resolve_devices(const std::vector<std::string>& specs, const std::vector<DeviceInfo>& all) {
  std::vector<DeviceInfo> out;
  for (const std::string& spec : specs)
    for (const DeviceInfo& d : select_devices(all, spec)) out.push_back(d);
  return out;
}

// The request of one matrix cell (clpt's kernel cache off: the row times builds).
RenderRequest cell_request(const Scene& scene, const BenchConfig& c, ExecutionForm form, bool generic,
                           Precision precision, size_t local_size, MegakernelLoop loop) {
  RenderRequest request;
  request.scene = scene;
  request.form = form;
  request.megakernel_loop = loop;
  request.precision = precision;
  request.generic_kernel = generic;
  request.local_size = local_size;
  request.cpu_vector_bits = c.cpu_vector_bits;
  request.sphere_reads = c.sphere_reads;
  request.paths_in_flight = c.paths_in_flight;
  request.use_kernel_cache = false;
  return request;
}

// One matrix cell, run as a render runs it: one plan (render_plan.h), its device pool and the
// same passes (launches sized as in a render). Builds cold (options no driver cache has seen),
// then twice more, the second timed (the driver's cache, clpt's own off), warms up, times
// `repeat` passes of c.spp samples per pixel.
BenchRow bench_cell(const BenchConfig& c, const Scene& scene, const DeviceInfo& device, ExecutionForm form,
                    bool generic, Precision precision, size_t local_size, MegakernelLoop loop, BvhBuilder builder) {
  BenchRow row;
  row.scene = scene.file;
  row.form = execution_form_name(form);
  row.kernel = generic ? "generic" : "specialised";
  row.precision = precision_name(precision);
  row.estimator = scene.settings.estimator;
  row.device = device.name;
  const RenderRequest request = cell_request(scene, c, form, generic, precision, local_size, loop);
  const RenderPlan plan = plan_render(request, {device});
  const DevicePlan& planned = plan.devices.front();
  const DeviceScene ds = make_device_scene(scene, c.width, c.height, precision, builder, plan.loop_meshes_apart);
  row.bvh_builder = bvh_builder_name(builder);
  row.triangles = ds.triangles.size();
  row.hierarchy_spheres = ds.bvh.sphere_order.size();
  row.bvh_nodes = ds.bvh.nodes.size();
  row.bvh_depth = ds.bvh.depth;
  row.bvh_stack_need = ds.bvh.stack_need;
  row.bvh_build_s = ds.bvh.build_seconds;
  row.bvh_build_threads = ds.bvh.build_threads;
  row.bvh_build_cpu_s = ds.bvh.build_cpu_seconds;
  StatsRaySample sample;
  if (!ds.bvh.nodes.empty()) {
    row.sah_cost = bvh_sah_cost(ds.bvh);
    sample = stats_rays(ds, c.width, c.height);
    const TraversalCounts counts = measure_traversal(ds, sample, planned.features.loop_beside_hierarchy()).all();
    row.stats_rays = counts.rays;
    row.stats_camera_rays = sample.camera_rays;
    row.nodes_per_ray = counts.per_ray(counts.nodes);
    row.boxes_per_ray = counts.per_ray(counts.boxes);
    row.triangles_per_ray = counts.per_ray(counts.triangles);
    row.spheres_per_ray = counts.per_ray(counts.hierarchy_spheres);
    row.loop_triangles_per_ray = counts.per_ray(counts.loop_triangles);
  }
  // Rows whose queries go past the sphere loop: triangles (in the hierarchy or the triangle loop), or
  // spheres in the hierarchy. trace.cl and the anchor test those primitives alone.
  const bool queries_beyond_loop = row.triangles > 0 || row.hierarchy_spheres > 0;
  if (!c.traversal_anchor.empty() && queries_beyond_loop) {
    const std::vector<GpuSphere> hierarchy_spheres(ds.spheres.begin() + ds.loop_spheres, ds.spheres.end());
    row.anchor = time_embree_anchor(ds.triangles, hierarchy_spheres, sample,
                                    int(std::max(1u, std::thread::hardware_concurrency())), 0.5,
                                    c.traversal_anchor_width);
  }
  if (c.traversal_alone && queries_beyond_loop)
    row.trace = time_clpt_trace(device, planned.features, ds, make_params(scene, ds), sample, 0.5);
  if (row.triangles > 0)
    row.device_bytes_per_triangle =
        double(row.triangles * (sizeof(GpuTriangle) + sizeof(GpuTriangleShading)) + hierarchy_device_bytes(ds)) /
        double(row.triangles);

  RenderPlan cold = plan;
  cold.devices.front().features.build_nonce = std::random_device{}() | 1u;
  row.build_cold_s = DevicePool(cold, ds, FaultPlan()).shares().front().build_seconds;
  { DevicePool fill_driver_cache(plan, ds, FaultPlan()); }
  DevicePool pool(plan, ds, FaultPlan());
  row.build_cached_s = pool.shares().front().build_seconds;
  row.local_size = planned.local_size;
  row.cpu_vector_bits = planned.features.cpu_vector_lanes == 0 ? "default" : "512";
  row.sphere_reads = reads_spheres_by_select(planned.features) ? "selects" : "indexed";
  if (form == ExecutionForm::Megakernel) row.loop = planned.features.lockstep_group ? "lockstep" : "path";
  row.paths_in_flight = planned.paths_in_flight;

  GpuRenderParams params = make_params(scene, ds);
  params.samples_per_pass = std::min(c.spp, pool.max_samples_per_pass(params.pixel_count));
  std::vector<double> paths_per_s, segments_per_s, paths_per_cpu_s;
  std::map<std::string, std::vector<double>> stage_runs;
  std::map<std::string, double> stage_before;
  for (int run = 0; run < c.warmup + c.repeat; ++run) {
    Film film(c.width, c.height);
    params.sample_begin = static_cast<cl_uint>(run) * params.samples_per_pass;
    const auto t0 = Clock::now();
    const double cpu0 = process_cpu_seconds();
    pool.run_pass(params, film);
    const double s = seconds_since(t0);
    const double cpu_s = process_cpu_seconds() - cpu0;
    for (const StageTime& t : pool.stage_times()) {
      if (run >= c.warmup) stage_runs[t.label].push_back(t.seconds - stage_before[t.label]);
      stage_before[t.label] = t.seconds;
    }
    if (run < c.warmup) continue;
    paths_per_s.push_back(double(film.total_samples()) / s);
    segments_per_s.push_back(double(film.total_segments()) / s);
    paths_per_cpu_s.push_back(double(film.total_samples()) / std::max(cpu_s, 1e-9));
  }
  row.paths_per_s = spread_of(paths_per_s);
  row.segments_per_s = spread_of(segments_per_s);
  row.paths_per_cpu_s = spread_of(paths_per_cpu_s);
  for (const auto& [label, v] : stage_runs) row.stage_seconds.emplace_back(label, spread_of(v).median);
  // After the timed runs, so that the probe's compile in another process overlaps none of them.
  if (c.measure_vector_width) row.vector_width = probe_vector_width(request, planned, this_executable());
  return row;
}

// Collective over `group`: `work` on the ranks where `takes_part` (rank 0 always), while the
// others idle (idle_barrier). A JobError from `work` (thrown together on every rank taking part,
// rank 0 among them) is rethrown on every rank of `group`, so that all of them leave the job in
// order rather than some waiting for ever.
void on_some_ranks(RankGroup& group, bool takes_part, const std::function<void()>& work) {
  ByteWriter status;  // empty: `work` succeeded
  if (takes_part) try {
      work();
    } catch (const JobError& e) {
      status.put(int32_t(e.code())).put(std::string(e.what()));
    }
  group.idle_barrier();
  group.broadcast(status.bytes());
  if (status.bytes().empty()) return;
  ByteReader reader(status.bytes());
  const auto code = ExitCode(reader.get<int32_t>());
  throw JobError(code, reader.get_string());
}

// Collective over `group`: the cell's render (run_render, c.spp samples per pixel) on its first
// n ranks for n = 1 .. K, the ranks past n idle; at rank 0 the rates (RankRate), elsewhere none.
std::vector<RankRate> rank_scaling(const BenchConfig& c, RenderRequest request, const DeviceInfo& device,
                                   RankGroup& group) {
  request.device = std::to_string(device.index);  // each rank's device of that index
  request.scene.settings.spp = c.spp;
  request.use_kernel_cache = true;  // the builds are not timed here
  std::vector<RankRate> out;
  for (int n = 1; n <= group.size(); ++n) {
    const std::unique_ptr<RankGroup> sub = group.first_ranks(n);
    std::vector<double> rates;
    on_some_ranks(group, sub != nullptr, [&] {
      request.ranks = sub.get();
      for (int run = 0; run < c.warmup + c.repeat; ++run) {
        RenderReport report;
        run_render(request, report);
        if (run >= c.warmup) rates.push_back(double(report.paths) / std::max(report.pass_seconds, 1e-9));
      }
    });
    if (!group.coordinator()) continue;
    RankRate rate;
    rate.ranks = n;
    rate.paths_per_s = spread_of(rates);
    const double one_rank = out.empty() ? rate.paths_per_s.median : out.front().paths_per_s.median;
    rate.efficiency = rate.paths_per_s.median / (n * one_rank);
    out.push_back(rate);
  }
  return out;
}

// One row of the matrix: bench_cell; in an MPI job bench_cell on rank 0 alone, then the scaling.
BenchRow bench_row(const BenchConfig& c, const Scene& scene, const DeviceInfo& device, ExecutionForm form,
                   bool generic, Precision precision, size_t local_size, MegakernelLoop loop, BvhBuilder builder) {
  if (!c.ranks || c.ranks->size() == 1)
    return bench_cell(c, scene, device, form, generic, precision, local_size, loop, builder);
  RankGroup& group = *c.ranks;
  BenchRow row;
  on_some_ranks(group, group.coordinator(),
                [&] { row = bench_cell(c, scene, device, form, generic, precision, local_size, loop, builder); });
  row.ranks = rank_scaling(c, cell_request(scene, c, form, generic, precision, local_size, loop), device, group);
  return row;
}

// The table's "lanes" column: the kernel's vector width (VectorWidthReport::lanes), "?" where
// unknown, "-" where not measured.
std::string lanes_cell(const BenchRow& r) {
  if (!r.vector_width) return "-";
  return r.vector_width->known ? std::to_string(r.vector_width->lanes) : "?";
}

nlohmann::json vector_width_json(const BenchRow& r) {
  if (!r.vector_width) return {{"lanes", nullptr}, {"widest", nullptr}, {"why", "not measured (--no-vector-width)"}};
  const VectorWidthReport& v = *r.vector_width;
  if (!v.known) return {{"lanes", nullptr}, {"widest", nullptr}, {"why", v.why}};
  nlohmann::json loops = nlohmann::json::object();
  for (const auto& [width, count] : v.loops_by_width) loops[std::to_string(width)] = count;
  nlohmann::json blockers = nlohmann::json::object();
  for (const auto& [reason, count] : v.blockers) blockers[reason] = count;
  return {{"lanes", v.lanes}, {"widest", v.widest}, {"loops", loops}, {"not_vectorised", v.not_vectorised},
          {"blockers", blockers}};
}

// What the anchor's scene holds, for its line: "32 triangles", "1000 spheres", or both.
std::string anchor_primitives(const AnchorRates& a) {
  std::string out;
  if (a.triangles > 0) out = std::to_string(a.triangles) + " triangles";
  if (a.spheres > 0) out += (out.empty() ? "" : " and ") + std::to_string(a.spheres) + " spheres";
  return out;
}

// clpt's closest-hit rays per CPU-second: its paths per CPU-second times segments per path.
double rays_per_cpu_s(const BenchRow& r) {
  return r.paths_per_s.median > 0 ? r.paths_per_cpu_s.median * r.segments_per_s.median / r.paths_per_s.median : 0;
}

std::string format_rate(const Spread& s) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f [%.2f-%.2f]", s.median * 1e-6, s.min * 1e-6, s.max * 1e-6);
  return buf;
}

}  // namespace

std::string BenchRow::key() const {
  return scene + "|" + form + (loop.empty() ? "" : ":" + loop) + "|" + kernel + "|" + precision + "|" +
         estimator + "|" + device + "|" + std::to_string(local_size) + (bvh_builder == "clpt" ? "" : "|bvh=" + bvh_builder) +
         (cpu_vector_bits == "default" ? "" : "|bits=" + cpu_vector_bits);
}

std::vector<BenchRow> run_bench(const BenchConfig& c, bool show_progress) {
  const std::vector<DeviceInfo> all = list_devices();
  std::vector<BenchRow> rows;
  for (const DeviceInfo& d : resolve_devices(c.devices, all)) {
    const DeviceInfo* device = &d;
    for (const std::string& file : c.scenes)
      for (const std::string& estimator : c.estimators) {
        Scene scene = load_scene_file(file);
        scene.settings.width = c.width;
        scene.settings.height = c.height;
        scene.settings.sampler = c.sampler;
        if (!estimator.empty()) scene.settings.estimator = estimator;
        for (Precision precision : c.precisions) {
          if (precision == Precision::Double && !device->fp64) {
            std::fprintf(stderr, "bench: skipping --precisions double on %s: no cl_khr_fp64\n", device->label().c_str());
            continue;
          }
          for (ExecutionForm form : c.forms)
            for (MegakernelLoop loop : c.megakernel_loops) {
              // The loop is the megakernel's: the wavefront runs once, whatever the list.
              if (form == ExecutionForm::Wavefront && loop != c.megakernel_loops.front()) continue;
              for (bool generic : c.generic)
                for (size_t local_size : c.local_sizes)
                  for (BvhBuilder builder : c.bvh_builders) {
                    if (show_progress)
                      std::fprintf(stderr, "bench: %s, %s, %s, %s%s%s, %s kernel, local size %zu, %s builder, %s\n",
                                   file.c_str(), scene.settings.estimator.c_str(), precision_name(precision),
                                   execution_form_name(form), form == ExecutionForm::Megakernel ? " loop " : "",
                                   form == ExecutionForm::Megakernel ? megakernel_loop_name(loop) : "",
                                   generic ? "generic" : "specialised", local_size, bvh_builder_name(builder),
                                   device->name.c_str());
                    rows.push_back(bench_row(c, scene, *device, form, generic, precision, local_size, loop, builder));
                  }
            }
        }
      }
  }
  return rows;
}

std::string bench_table(const std::vector<BenchRow>& rows) {
  std::ostringstream o;
  char line[512];
  std::snprintf(line, sizeof line, "%-22s %-10s %-8s %-11s %-6s %-4s %-5s %-24s %-24s %-16s %-13s %-5s %s\n",
                "scene", "form", "loop", "kernel", "prec", "est", "wg", "M paths/s med [min-max]",
                "M segments/s med [min-max]", "M paths/CPU-s", "build cold/cached s", "lanes", "device");
  o << line;
  for (const BenchRow& r : rows) {
    char build[32];
    std::snprintf(build, sizeof build, "%.2f/%.2f", r.build_cold_s, r.build_cached_s);
    char per_cpu[32];
    std::snprintf(per_cpu, sizeof per_cpu, "%.2f", r.paths_per_cpu_s.median * 1e-6);
    std::snprintf(line, sizeof line, "%-22s %-10s %-8s %-11s %-6s %-4s %-5s %-24s %-24s %-16s %-13s %-5s %s\n",
                  r.scene.c_str(), r.form.c_str(), r.loop.empty() ? "-" : r.loop.c_str(), r.kernel.c_str(),
                  r.precision.c_str(), r.estimator.c_str(),
                  r.local_size ? std::to_string(r.local_size).c_str() : "auto",
                  format_rate(r.paths_per_s).c_str(), format_rate(r.segments_per_s).c_str(), per_cpu, build,
                  lanes_cell(r).c_str(), (r.device + (r.cpu_vector_bits == "512" ? " (512-bit vectors)" : "")).c_str());
    o << line;
    if (r.vector_width) o << "    vector width: " << r.vector_width->describe() << "\n";
    if (!r.stage_seconds.empty()) {
      o << "    stages (median s/run):";
      for (const auto& [label, s] : r.stage_seconds) {
        std::snprintf(line, sizeof line, " %s %.4f", label.c_str(), s);
        o << line;
      }
      o << "; " << r.paths_in_flight << " paths in flight\n";
    }
    if (r.bvh_nodes > 0) {
      std::snprintf(line, sizeof line,
                    "    hierarchy: %llu triangles, %llu spheres, %llu 4-wide nodes, depth %d, stack %d, built in %.4f s (%.4f CPU-s) on "
                    "the host (%s builder, %d thread%s); %.1f device B/triangle\n",
                    static_cast<unsigned long long>(r.triangles), static_cast<unsigned long long>(r.hierarchy_spheres),
                    static_cast<unsigned long long>(r.bvh_nodes), r.bvh_depth, r.bvh_stack_need, r.bvh_build_s, r.bvh_build_cpu_s,
                    r.bvh_builder.c_str(), r.bvh_build_threads, r.bvh_build_threads == 1 ? "" : "s",
                    r.device_bytes_per_triangle);
      o << line;
      std::snprintf(line, sizeof line,
                    "    traversal: SAH cost %.2f; per ray %.1f nodes, %.1f boxes, %.1f triangles, %.1f spheres%s "
                    "(replica over %llu rays: %llu camera + %llu bounce)\n",
                    r.sah_cost, r.nodes_per_ray, r.boxes_per_ray, r.triangles_per_ray, r.spheres_per_ray,
                    r.loop_triangles_per_ray > 0
                        ? (", beside " + std::to_string(int(r.loop_triangles_per_ray + 0.5)) + " in the triangle loop").c_str()
                        : "",
                    static_cast<unsigned long long>(r.stats_rays), static_cast<unsigned long long>(r.stats_camera_rays),
                    static_cast<unsigned long long>(r.stats_rays - r.stats_camera_rays));
      o << line;
    }
    if (r.anchor) {
      const AnchorRates& a = *r.anchor;
      const double clpt_cpu = rays_per_cpu_s(r);
      std::snprintf(line, sizeof line,
                    "    anchor: clpt %.2f M rays/s (segments/s), %.2f M/CPU-s; %s on %d thread%s, the same %s "
                    "and %llu rays: rtcIntersect1%s %.2f M rays/s, %.2f M/CPU-s, rtcIntersect16 %.2f M rays/s, %.2f "
                    "M/CPU-s; robust, as Cycles builds it: rtcIntersect1 %.2f M rays/s, %.2f M/CPU-s; "
                    "clpt/rtcIntersect1 %.3f (per CPU-s %.3f)\n",
                    r.segments_per_s.median * 1e-6, clpt_cpu * 1e-6, a.name.c_str(), a.threads, a.threads == 1 ? "" : "s",
                    anchor_primitives(a).c_str(), static_cast<unsigned long long>(a.rays),
                    a.tri_accel.empty() ? "" : (" (" + a.tri_accel + ")").c_str(), a.single_per_s * 1e-6, a.single_per_cpu_s * 1e-6,
                    a.packet16_per_s * 1e-6, a.packet16_per_cpu_s * 1e-6, a.robust_single_per_s * 1e-6,
                    a.robust_single_per_cpu_s * 1e-6,
                    a.single_per_s > 0 ? r.segments_per_s.median / a.single_per_s : 0.0,
                    a.single_per_cpu_s > 0 ? clpt_cpu / a.single_per_cpu_s : 0.0);
      o << line;
    }
    if (r.trace) {
      const TraceRates& t = *r.trace;
      std::snprintf(line, sizeof line,
                    "    traversal alone: clpt (trace.cl, the row's options) %.2f M rays/s, %.2f M/CPU-s, %llu of %llu "
                    "rays hit",
                    t.per_s * 1e-6, t.per_cpu_s * 1e-6, static_cast<unsigned long long>(t.hits),
                    static_cast<unsigned long long>(t.rays));
      o << line;
      if (r.anchor) {
        const AnchorRates& a = *r.anchor;
        std::snprintf(line, sizeof line,
                      " (embree %llu); clpt/rtcIntersect1 %.3f (per CPU-s %.3f), against the robust scene %.3f "
                      "(per CPU-s %.3f)",
                      static_cast<unsigned long long>(a.hits), a.single_per_s > 0 ? t.per_s / a.single_per_s : 0.0,
                      a.single_per_cpu_s > 0 ? t.per_cpu_s / a.single_per_cpu_s : 0.0,
                      a.robust_single_per_s > 0 ? t.per_s / a.robust_single_per_s : 0.0,
                      a.robust_single_per_cpu_s > 0 ? t.per_cpu_s / a.robust_single_per_cpu_s : 0.0);
        o << line;
      }
      o << "\n";
    }
    for (const RankRate& k : r.ranks) {
      std::snprintf(line, sizeof line, "    on %d MPI rank%s: M paths/s %s, efficiency %.0f%%\n", k.ranks,
                    k.ranks == 1 ? "" : "s", format_rate(k.paths_per_s).c_str(), 100 * k.efficiency);
      o << line;
    }
  }
  return o.str();
}

std::string bench_json(const std::vector<BenchRow>& rows, const BenchConfig& c) {
  nlohmann::json j;
  j["clpt_version"] = CLPT_VERSION;
  j["config"] = {{"width", c.width}, {"height", c.height}, {"spp", c.spp},
                 {"warmup", c.warmup}, {"repeat", c.repeat}};
  j["rows"] = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    nlohmann::json stages = nlohmann::json::object();
    for (const auto& [label, s] : r.stage_seconds) stages[label] = s;
    auto spread = [](const Spread& s) {
      return nlohmann::json{{"median", s.median}, {"min", s.min}, {"max", s.max}};
    };
    nlohmann::json row = {{"key", r.key()}, {"scene", r.scene}, {"form", r.form}, {"loop", r.loop},
                          {"kernel", r.kernel}, {"precision", r.precision}, {"estimator", r.estimator},
                          {"device", r.device}, {"local_size", r.local_size}, {"cpu_vector_bits", r.cpu_vector_bits},
                          {"sphere_reads", r.sphere_reads}, {"paths_in_flight", r.paths_in_flight},
                          {"build_cold_s", r.build_cold_s}, {"build_cached_s", r.build_cached_s},
                          {"triangles", r.triangles}, {"hierarchy_spheres", r.hierarchy_spheres},
                          {"bvh_builder", r.bvh_builder}, {"bvh_nodes", r.bvh_nodes}, {"bvh_depth", r.bvh_depth}, {"bvh_stack_need", r.bvh_stack_need}, {"bvh_build_s", r.bvh_build_s},
                          {"device_bytes_per_triangle", r.device_bytes_per_triangle},
                          {"bvh_build_threads", r.bvh_build_threads}, {"bvh_build_cpu_s", r.bvh_build_cpu_s}, {"sah_cost", r.sah_cost},
                          {"traversal", {{"rays", r.stats_rays}, {"camera_rays", r.stats_camera_rays},
                                         {"nodes_per_ray", r.nodes_per_ray}, {"boxes_per_ray", r.boxes_per_ray},
                                         {"triangles_per_ray", r.triangles_per_ray},
                                         {"spheres_per_ray", r.spheres_per_ray},
                                         {"loop_triangles_per_ray", r.loop_triangles_per_ray}}},
                          {"rays_per_s", r.segments_per_s.median}, {"rays_per_cpu_s", rays_per_cpu_s(r)},
                          {"paths_per_s", spread(r.paths_per_s)},
                          {"segments_per_s", spread(r.segments_per_s)}, {"paths_per_cpu_s", spread(r.paths_per_cpu_s)},
                          {"stage_seconds", stages}, {"vector_width", vector_width_json(r)}};
    if (r.anchor)
      row["anchor"] = {{"name", r.anchor->name}, {"threads", r.anchor->threads}, {"rays", r.anchor->rays},
                       {"triangles", r.anchor->triangles}, {"spheres", r.anchor->spheres},
                       {"tri_accel", r.anchor->tri_accel.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.anchor->tri_accel)},
                       {"hits", r.anchor->hits}, {"build_s", r.anchor->build_s},
                       {"rtcIntersect1_rays_per_s", r.anchor->single_per_s},
                       {"rtcIntersect16_rays_per_s", r.anchor->packet16_per_s},
                       {"rtcIntersect1_rays_per_cpu_s", r.anchor->single_per_cpu_s},
                       {"rtcIntersect16_rays_per_cpu_s", r.anchor->packet16_per_cpu_s},
                       {"robust", {{"flags", "RTC_SCENE_FLAG_ROBUST"}, {"build_quality", "medium"},
                                   {"hits", r.anchor->robust_hits}, {"build_s", r.anchor->robust_build_s},
                                   {"rtcIntersect1_rays_per_s", r.anchor->robust_single_per_s},
                                   {"rtcIntersect1_rays_per_cpu_s", r.anchor->robust_single_per_cpu_s}}}};
    if (r.trace)
      row["trace"] = {{"rays", r.trace->rays}, {"hits", r.trace->hits}, {"launch_rays", r.trace->launch_rays},
                      {"rays_per_s", r.trace->per_s}, {"rays_per_cpu_s", r.trace->per_cpu_s}};
    if (!r.ranks.empty()) {
      row["ranks"] = nlohmann::json::array();
      for (const RankRate& k : r.ranks)
        row["ranks"].push_back({{"ranks", k.ranks}, {"paths_per_s", spread(k.paths_per_s)}, {"efficiency", k.efficiency}});
    }
    j["rows"].push_back(row);
  }
  return j.dump(2) + "\n";
}

std::vector<std::string> bench_regressions(const std::vector<BenchRow>& rows,
                                           const std::string& baseline_path,
                                           double tolerance_percent) {
  std::ifstream in(baseline_path);
  if (!in) throw Error(ExitCode::Usage, "--baseline " + baseline_path + ": cannot open file");
  nlohmann::json base;
  try {
    base = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw Error(ExitCode::Usage, "--baseline " + baseline_path + ": not a bench JSON file: " + e.what());
  }
  std::map<std::string, double> baseline;
  for (const auto& row : base.value("rows", nlohmann::json::array()))
    baseline[row.value("key", "")] = row["paths_per_s"].value("median", 0.0);
  std::vector<std::string> out;
  for (const BenchRow& r : rows) {
    const auto it = baseline.find(r.key());
    if (it == baseline.end() || it->second <= 0) continue;
    const double change = 100.0 * (r.paths_per_s.median / it->second - 1.0);
    if (change < -tolerance_percent) {
      char line[512];
      std::snprintf(line, sizeof line, "%s: %.3f M paths/s, baseline %.3f (%.1f%%, limit -%.1f%%)",
                    r.key().c_str(), r.paths_per_s.median * 1e-6, it->second * 1e-6, change,
                    tolerance_percent);
      out.push_back(line);
    }
  }
  return out;
}

}  // namespace clpt
