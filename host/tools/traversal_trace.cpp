// clpt's closest-hit rate on the anchor's rays (traversal_trace.h).
#include "tools/traversal_trace.h"

#include <algorithm>
#include <vector>

#include "cl/cl_context.h"
#include "kernels/kernel_source.h"
#include "render/renderer.h"
#include "util/clock.h"

namespace clpt {

TraceRates time_clpt_trace(const DeviceInfo& device, const KernelFeatures& features, const DeviceScene& ds,
                           const GpuRenderParams& params, const StatsRaySample& sample, double min_seconds) {
  TraceRates out;
  out.rays = sample.rays.size();
  if (sample.rays.empty()) return out;
  DeviceContext ctx(device);
  const ProgramHandle program =
      ctx.build_program(assemble_kernel_source("trace.cl"), kernel_build_options(features), "trace.cl");
  Kernel kernel(program.get(), "trace_hierarchy", ctx.where(), features.cpu_vector_lanes, !features.triangles_in_loop());
  const Renderer::SceneBufferSet scene = Renderer::upload_scene(ctx, ds);

  // The sample repeated to about 64k rays a launch on PoCL (within its one-compile launch size,
  // DeviceInfo::uniform_launch_limit), about a million elsewhere (a GPU needs that many to fill).
  const size_t n = sample.rays.size();
  const size_t limit = device.uniform_launch_limit() ? std::min<size_t>(65536, device.uniform_launch_limit()) : 1u << 20;
  const size_t copies = std::max<size_t>(1, limit / n);
  const size_t count = copies * n;
  out.launch_rays = count;
  std::vector<cl_float4> rays(2 * count);  // per ray: origin, 0, direction, 0 (trace.cl reads 8 floats)
  for (size_t i = 0; i < count; ++i) {
    const StatsRay& r = sample.rays[i % n];
    rays[2 * i] = {{float(r.origin[0]), float(r.origin[1]), float(r.origin[2]), 0.f}};
    rays[2 * i + 1] = {{float(r.direction[0]), float(r.direction[1]), float(r.direction[2]), 0.f}};
  }
  Buffer ray_buffer(ctx, rays.size() * sizeof(cl_float4), CL_MEM_READ_ONLY, "trace rays");
  ctx.write(ray_buffer, rays.data(), rays.size() * sizeof(cl_float4));
  Buffer t_buffer(ctx, count * sizeof(float), CL_MEM_WRITE_ONLY, "trace distances");
  cl_uint arg = Renderer::bind_scene(kernel, 0, scene);
  kernel.set_arg(arg++, params);
  kernel.set_arg(arg++, ray_buffer);
  kernel.set_arg(arg++, cl_uint(count));
  kernel.set_arg(arg++, t_buffer);

  // A work-group of 64, as the per-path megakernel's on PoCL (render_plan.cpp).
  const size_t local = 64;
  ctx.launch(kernel, count, local, "trace_hierarchy");  // untimed: PoCL compiles here
  ctx.finish();
  std::vector<float> t(count);
  ctx.read(t_buffer, t.data(), count * sizeof(float));
  for (size_t i = 0; i < n; ++i) out.hits += t[i] < 1e29f;  // a miss is CLPT_NO_HIT, 1e30 (maths.cl)

  uint64_t launches = 0;
  const auto start = Clock::now();
  const double cpu_start = process_cpu_seconds();
  double elapsed = 0;
  // Launches queued eight at a time, as a render keeps its queue fed: waiting for each launch of
  // 64k rays before queueing the next left one of PoCL's two threads idle 40% of the time
  // (2026-12-06, 2-core VM).
  const int batch = 8;
  do {
    for (int b = 0; b < batch; ++b) ctx.launch(kernel, count, local, "trace_hierarchy");
    ctx.finish();
    launches += batch;
    elapsed = seconds_since(start);
  } while (elapsed < min_seconds);
  const double traced = double(launches) * double(count);
  out.per_s = traced / elapsed;
  out.per_cpu_s = traced / std::max(process_cpu_seconds() - cpu_start, 1e-9);
  return out;
}

}  // namespace clpt
