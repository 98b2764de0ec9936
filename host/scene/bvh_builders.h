// Which builder makes the kernels' hierarchy: clpt's own binned SAH builder (bvh_build.h), the
// default and the only one renders use, or Embree's rtcBuildBVH (bvh_embree.h, in a build that
// found Embree), kept to measure against it: `clpt bench --bvh-builders` (docs/performance.md,
// "Traversal"). Both write the same layout, so the kernels cannot tell them apart.
#pragma once

#include <string>
#include <vector>

#include "scene/bvh_build.h"

namespace clpt {

enum class BvhBuilder {
  Clpt,             // build_bvh on one thread per hardware thread (the hierarchy is the same for any count)
  ClptOneThread,    // build_bvh on one thread, for the parallel build's speed-up
  Embree,           // rtcBuildBVH on Embree's default threads (one per hardware thread)
  EmbreeOneThread,  // rtcBuildBVH on one thread, for a like-for-like build time
};

const char* bvh_builder_name(BvhBuilder builder);  // "clpt", "clpt-1thread", "embree", "embree-1thread"

// Whether this build has Embree (CMake found libembree-dev: CLPT_WITH_EMBREE).
bool embree_available();

// `name` as bvh_builder_name spells it; throws Error(ExitCode::Usage) naming `option` for an
// unknown name, and for an Embree builder in a build without Embree.
BvhBuilder parse_bvh_builder(const std::string& name, const std::string& option);

Bvh build_bvh_with(BvhBuilder builder, const std::vector<BvhPrimitive>& primitives,
                   const BvhBuildOptions& options = {});

}  // namespace clpt
