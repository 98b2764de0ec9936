// The kernels' hierarchy (bvh_build.h's Bvh, GpuBvhNode) built by Embree's rtcBuildBVH instead
// of clpt's own binned SAH builder: Embree 3 (Debian 12: libembree-dev 3.13.5) builds a binary
// tree of nodes clpt allocates through its callbacks, which is then flattened depth first into
// the same binary tree, leaves split by primitive kind as build_bvh does, and collapsed into the
// same 4-wide layout (collapse_bvh). Compiled only when CMake
// finds Embree (CLPT_WITH_EMBREE); it exists to measure the two builders against each other
// (`clpt bench --bvh-builders clpt,embree`, docs/performance.md "Traversal"): clpt's own is the
// default and the only one renders use.
#pragma once

#include <vector>

#include "scene/bvh_build.h"

namespace clpt {

// `threads`: Embree's worker threads (0: one per hardware thread, Embree's default). Spatial
// splits are off, so every primitive is in exactly one leaf, as the kernels' orders need.
// Throws Error (ExitCode::BadScene) for a hierarchy deeper than CLPT_BVH_STACK and
// Error(ExitCode::Failure) when Embree itself fails, with its error.
Bvh build_bvh_embree(const std::vector<BvhPrimitive>& primitives, const BvhBuildOptions& options, int threads);

}  // namespace clpt
