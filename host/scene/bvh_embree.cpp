// Embree's rtcBuildBVH into clpt's node layout (bvh_embree.h). Embree calls back to allocate
// nodes (from its own thread-local allocator, freed with the RTCBVH) and leaves; the tree it
// returns is then walked once to write the binary tree (BvhBinaryNode) depth first with clpt's own
// boxes (the union of the primitives' float boxes, so that a leaf's box contains what the kernels
// intersect), which collapse_bvh turns into the kernels' 4-wide nodes as for clpt's builder.
#include "scene/bvh_embree.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <memory>
#include <string>
#include <thread>

#include "util/clock.h"
#include "util/error.h"

namespace clpt {
namespace {

// What the callbacks build. Every node starts with its kind.
struct EmbreeInner {
  bool leaf = false;
  unsigned children = 0;
  const void* child[2] = {nullptr, nullptr};
};
struct EmbreeLeaf {
  bool leaf = true;
  unsigned count = 0;
  unsigned input[1];  // `count` positions in the input vector (allocated longer)
};

void* create_node(RTCThreadLocalAllocator alloc, unsigned int children, void*) {
  if (children > 2) return nullptr;  // maxBranchingFactor is 2; Embree reports a null node as an error
  return new (rtcThreadLocalAlloc(alloc, sizeof(EmbreeInner), 16)) EmbreeInner();
}

void set_children(void* node, void** children, unsigned int count, void*) {
  auto* inner = static_cast<EmbreeInner*>(node);
  inner->children = count;
  for (unsigned i = 0; i < count; ++i) inner->child[i] = children[i];
}

// clpt recomputes every box from the primitives while flattening.
void set_bounds(void*, const RTCBounds**, unsigned int, void*) {}

void* create_leaf(RTCThreadLocalAllocator alloc, const RTCBuildPrimitive* prims, size_t count, void*) {
  const size_t bytes = sizeof(EmbreeLeaf) + (count > 0 ? count - 1 : 0) * sizeof(unsigned);
  auto* leaf = new (rtcThreadLocalAlloc(alloc, bytes, 16)) EmbreeLeaf();
  leaf->count = static_cast<unsigned>(count);
  for (size_t i = 0; i < count; ++i) leaf->input[i] = prims[i].primID;
  return leaf;
}

struct Flattener {
  const std::vector<BvhPrimitive>& input;
  Bvh out;

  void set_box(uint32_t node, const BvhBox& box) {
    for (int k = 0; k < 3; ++k) {
      out.binary[node].lower[k] = box.lower[k];
      out.binary[node].upper[k] = box.upper[k];
    }
  }

  // Writes `prims` (non-empty) as one leaf, or as an interior node over a sphere leaf and a
  // triangle leaf when they mix kinds (the kernels' leaves hold one kind). Returns the box.
  BvhBox leaf(std::vector<BvhPrimitive> prims, int depth) {
    note_bvh_depth(out, depth);
    BvhBox box;
    for (const BvhPrimitive& p : prims) box.grow(p.box);
    const uint32_t node = push_bvh_node(out, box);
    const auto triangles = std::stable_partition(prims.begin(), prims.end(),
                                                 [](const BvhPrimitive& p) { return p.kind == PrimitiveKind::Sphere; });
    if (triangles == prims.begin() || triangles == prims.end()) {
      make_bvh_leaf(out, node, prims.data(), prims.data() + prims.size());
      return box;
    }
    const size_t spheres = size_t(triangles - prims.begin());
    note_bvh_depth(out, depth + 1);
    BvhBox part;
    for (size_t i = 0; i < spheres; ++i) part.grow(prims[i].box);
    make_bvh_leaf(out, push_bvh_node(out, part), prims.data(), prims.data() + spheres);
    out.binary[node].first = static_cast<uint32_t>(out.binary.size());
    out.binary[node].count = 0;
    part = BvhBox();
    for (size_t i = spheres; i < prims.size(); ++i) part.grow(prims[i].box);
    make_bvh_leaf(out, push_bvh_node(out, part), prims.data() + spheres, prims.data() + prims.size());
    return box;
  }

  BvhBox node(const void* embree_node, int depth) {
    if (static_cast<const EmbreeLeaf*>(embree_node)->leaf) {
      const auto* l = static_cast<const EmbreeLeaf*>(embree_node);
      std::vector<BvhPrimitive> prims;
      for (unsigned i = 0; i < l->count; ++i) prims.push_back(input[l->input[i]]);
      return leaf(std::move(prims), depth);
    }
    const auto* inner = static_cast<const EmbreeInner*>(embree_node);
    if (inner->children == 1) return node(inner->child[0], depth);
    note_bvh_depth(out, depth);
    const uint32_t self = push_bvh_node(out, BvhBox());
    BvhBox box = node(inner->child[0], depth + 1);
    out.binary[self].first = static_cast<uint32_t>(out.binary.size());
    out.binary[self].count = 0;
    box.grow(node(inner->child[1], depth + 1));
    set_box(self, box);
    return box;
  }
};

[[noreturn]] void embree_failed(RTCDevice device, const char* what) {
  const RTCError code = device ? rtcGetDeviceError(device) : RTC_ERROR_UNKNOWN;
  throw Error(ExitCode::Failure, std::string("Embree: ") + what + " (RTCError " + std::to_string(int(code)) + ")");
}

}  // namespace

Bvh build_bvh_embree(const std::vector<BvhPrimitive>& primitives, const BvhBuildOptions& options, int threads) {
  const auto start = Clock::now();
  Flattener flat{primitives, {}};
  if (!primitives.empty()) {
    const std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
    std::unique_ptr<RTCDeviceTy, void (*)(RTCDevice)> device(rtcNewDevice(config.empty() ? nullptr : config.c_str()),
                                                             &rtcReleaseDevice);
    if (!device) embree_failed(nullptr, "rtcNewDevice failed");
    std::unique_ptr<RTCBVHTy, void (*)(RTCBVH)> bvh(rtcNewBVH(device.get()), &rtcReleaseBVH);
    if (!bvh) embree_failed(device.get(), "rtcNewBVH failed");
    std::vector<RTCBuildPrimitive> prims(primitives.size());
    for (size_t i = 0; i < primitives.size(); ++i) {
      const BvhBox& b = primitives[i].box;
      prims[i] = {b.lower[0], b.lower[1], b.lower[2], 0, b.upper[0], b.upper[1], b.upper[2], static_cast<unsigned>(i)};
    }
    RTCBuildArguments args = rtcDefaultBuildArguments();
    args.buildQuality = RTC_BUILD_QUALITY_MEDIUM;  // binned SAH, as clpt's; no spatial splits
    args.maxBranchingFactor = 2;
    args.maxDepth = CLPT_BVH_STACK - 1;  // one level left for splitting a mixed leaf by kind
    args.minLeafSize = 1;
    args.maxLeafSize = static_cast<unsigned>(options.max_leaf);
    args.traversalCost = static_cast<float>(options.traversal_cost);
    args.intersectionCost = 1.0f;
    args.bvh = bvh.get();
    args.primitives = prims.data();
    args.primitiveCount = prims.size();
    args.primitiveArrayCapacity = prims.size();
    args.createNode = create_node;
    args.setNodeChildren = set_children;
    args.setNodeBounds = set_bounds;
    args.createLeaf = create_leaf;
    const void* root = rtcBuildBVH(&args);
    if (!root) embree_failed(device.get(), "rtcBuildBVH failed");
    flat.out.binary.reserve(2 * primitives.size());
    flat.node(root, 1);
  }
  collapse_bvh(flat.out);
  flat.out.build_seconds = seconds_since(start);
  flat.out.build_threads = threads > 0 ? threads : std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return std::move(flat.out);
}

}  // namespace clpt
