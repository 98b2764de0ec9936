// `clpt bench --traversal-anchor embree`: Embree's own closest-hit queries timed on a row's
// triangles (and hierarchy spheres) and rays, beside clpt's rays/s (docs/performance.md,
// "Traversal"). Only in a build that found libembree-dev (CMake: CLPT_WITH_EMBREE); renders never
// use it.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "kernels/types.h"
#include "scene/bvh_stats.h"

namespace clpt {

// Whether this build can time `name` ("embree": a build with Embree).
bool traversal_anchor_available(const std::string& name);

// Checks a --traversal-anchor value: "embree", in a build with Embree. Throws
// Error(ExitCode::Usage) naming `option` otherwise.
void check_traversal_anchor(const std::string& name, const std::string& option);

// Embree's closest-hit rates on `triangles` (the device scene's, camera-relative float, as the
// kernels intersect them) and `spheres` (the hierarchy's: Embree's sphere points, each the stored
// sphere's centre and radius) for the rays of `sample` (their origins and directions in float, from
// t = 0 when there are no spheres, else from each ray's t_min, the scene's ray epsilon, as
// trace.cl's sphere tests): rtcIntersect1 one ray per call, and rtcIntersect16 on packets of 16
// consecutive rays of the sample; on `threads` threads, each passing over its own slice of the
// sample again and again until min_seconds have passed. Two scenes, each built once (not timed):
// Embree's fastest for tracing (RTC_SCENE_FLAG_NONE, RTC_BUILD_QUALITY_HIGH: spatial splits, its
// non-robust tests), and Embree as Cycles builds a final render's hierarchy (RTC_SCENE_FLAG_ROBUST,
// which keeps rays from slipping between neighbouring triangles as clpt's watertight traversal
// does, and RTC_BUILD_QUALITY_MEDIUM, Cycles' default without spatial splits;
// intern/cycles/bvh/embree.cpp), timed with rtcIntersect1 alone. `width` 4 or 8 builds the fastest
// scene's triangles into Embree's tree of that width with its four-triangle leaves
// (tri_accel=bvh4.triangle4 or bvh8.triangle4, Embree's device configuration); 0 leaves Embree its
// choice.
struct AnchorRates {
  std::string name;            // "embree 3.13.5"
  std::string tri_accel;       // the fastest scene's forced tree over triangles ("bvh4.triangle4"), or ""
  int threads = 1;
  uint64_t triangles = 0, spheres = 0;  // the primitives Embree holds
  uint64_t rays = 0;           // per pass: the sample's rays
  uint64_t hits = 0;           // of one pass of rtcIntersect1 (a check: the same with packets)
  uint64_t packet_hits = 0;
  double build_s = 0;          // rtcCommitScene, for information
  double single_per_s = 0;     // rays/s, rtcIntersect1
  double packet16_per_s = 0;   // rays/s, rtcIntersect16
  // Rays per CPU-second of this process (all its threads) over the same passes: the figures that
  // hold while other work shares the cores, beside clpt's rays per CPU-second.
  double single_per_cpu_s = 0, packet16_per_cpu_s = 0;
  // The robust scene (as Cycles builds it): rtcIntersect1's rays/s and rays per CPU-second, the
  // hits of one pass, its build's seconds.
  double robust_single_per_s = 0, robust_single_per_cpu_s = 0;
  uint64_t robust_hits = 0;
  double robust_build_s = 0;
};
AnchorRates time_embree_anchor(const std::vector<GpuTriangle>& triangles, const std::vector<GpuSphere>& spheres,
                               const StatsRaySample& sample, int threads, double min_seconds, int width = 0);

}  // namespace clpt
