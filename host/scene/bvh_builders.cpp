// The choice of hierarchy builder (bvh_builders.h).
#include "scene/bvh_builders.h"

#include "util/error.h"

#ifdef CLPT_WITH_EMBREE
#include "scene/bvh_embree.h"
#endif

namespace clpt {

const char* bvh_builder_name(BvhBuilder builder) {
  switch (builder) {
    case BvhBuilder::Embree: return "embree";
    case BvhBuilder::EmbreeOneThread: return "embree-1thread";
    case BvhBuilder::ClptOneThread: return "clpt-1thread";
    case BvhBuilder::Clpt: break;
  }
  return "clpt";
}

bool embree_available() {
#ifdef CLPT_WITH_EMBREE
  return true;
#else
  return false;
#endif
}

BvhBuilder parse_bvh_builder(const std::string& name, const std::string& option) {
  for (BvhBuilder b : {BvhBuilder::Clpt, BvhBuilder::ClptOneThread, BvhBuilder::Embree, BvhBuilder::EmbreeOneThread}) {
    if (name != bvh_builder_name(b)) continue;
    const bool embree = b == BvhBuilder::Embree || b == BvhBuilder::EmbreeOneThread;
    if (embree && !embree_available())
      throw Error(ExitCode::Usage, option + " " + name + ": this clpt was built without Embree "
                                   "(install libembree-dev and reconfigure with CMake)");
    return b;
  }
  throw Error(ExitCode::Usage, option + ": unknown hierarchy builder '" + name +
                                   "' (expected clpt, clpt-1thread, embree or embree-1thread)");
}

Bvh build_bvh_with(BvhBuilder builder, const std::vector<BvhPrimitive>& primitives, const BvhBuildOptions& options) {
  const bool embree = builder == BvhBuilder::Embree || builder == BvhBuilder::EmbreeOneThread;
#ifdef CLPT_WITH_EMBREE
  if (embree) {
    // Embree's builder has its own leaf costs; its tree's SAH cost is reported in the same model.
    Bvh b = build_bvh_embree(primitives, options, builder == BvhBuilder::EmbreeOneThread ? 1 : 0);
    b.leaf_group = options.leaf_group;
    return b;
  }
#else
  if (embree)
    throw Error(ExitCode::Usage, std::string("hierarchy builder ") + bvh_builder_name(builder) +
                                     ": this clpt was built without Embree");
#endif
  if (builder == BvhBuilder::ClptOneThread) {
    BvhBuildOptions one = options;
    one.threads = 1;
    return build_bvh(primitives, one);
  }
  return build_bvh(primitives, options);
}

}  // namespace clpt
