// clpt's own closest-hit rate on the traversal statistics' rays (`clpt bench --traversal-alone`, and
// beside Embree's with `--traversal-anchor`):
// kernels/trace.cl, built with a bench row's kernel options, queries the row's triangles and
// hierarchy spheres alone (the triangle loop or the hierarchy, as the row's render does) for the rays of the statistics'
// sample, so that its rays/s compares with Embree's rtcIntersect1 on the same queries
// (tools/traversal_anchor.h). Needs no Embree; renders never build it.
#pragma once

#include <cstdint>

#include "cl/cl_device.h"
#include "kernels/kernel_options.h"
#include "kernels/types.h"
#include "scene/bvh_stats.h"
#include "scene/device_scene.h"

namespace clpt {

struct TraceRates {
  uint64_t rays = 0;       // per pass: the sample's rays
  uint64_t hits = 0;       // of one pass (beside the anchor's, a check that both answer alike)
  uint64_t launch_rays = 0;  // rays per launch: the sample repeated, to about 64k on PoCL and 1 M
                             // elsewhere (a launch of 4240 rays is mostly launch overhead)
  double per_s = 0;        // rays/s over whole launches (wall time on the host)
  double per_cpu_s = 0;    // rays per CPU-second of this process (PoCL's threads are in it)
};

// Builds trace.cl for `device` with `features` (the row's plan, kernel_options.h), uploads `ds`,
// then launches over the sample's rays (repeated to fill a launch; launches queued eight at a time)
// until min_seconds have passed, after one untimed launch (PoCL compiles at the first). `params`:
// make_params of the scene, for the hierarchy's node count. Throws as the renderers do on a device error.
TraceRates time_clpt_trace(const DeviceInfo& device, const KernelFeatures& features, const DeviceScene& ds,
                           const GpuRenderParams& params, const StatsRaySample& sample, double min_seconds);

}  // namespace clpt
