// Binned SAH construction of the kernels' hierarchy (bvh_build.h). Top down: at each node the
// primitives' centroids are binned along each axis, the plane with the least SAH cost
// (traversal_cost + (A_left N_left + A_right N_right) / A) wins against making a leaf (cost N),
// and the two sides are built recursively; the node array is filled depth first as it goes.
// Parallel with std::thread: a large node's right subtree is built on a spare thread into a
// subtree of its own, stitched after the left one as the serial build would have written it, and
// a very large node's binning pass is split over spare threads; every split is decided by the same
// serial rule on the same exact bins, so the hierarchy is the same for any number of threads
// (BvhBuild.SameTreeForAnyThreadCount).
#include "scene/bvh_build.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <string>
#include <thread>

#include "util/clock.h"
#include "util/error.h"

namespace clpt {

void BvhBox::grow(const BvhBox& b) {
  for (int k = 0; k < 3; ++k) {
    lower[k] = std::min(lower[k], b.lower[k]);
    upper[k] = std::max(upper[k], b.upper[k]);
  }
}

void BvhBox::grow(const std::array<float, 3>& p) {
  for (int k = 0; k < 3; ++k) {
    lower[k] = std::min(lower[k], p[k]);
    upper[k] = std::max(upper[k], p[k]);
  }
}

double BvhBox::half_area() const {
  if (lower[0] > upper[0]) return 0;
  const double x = double(upper[0]) - lower[0], y = double(upper[1]) - lower[1], z = double(upper[2]) - lower[2];
  return x * y + y * z + z * x;
}

BvhBox sphere_box(const std::array<double, 3>& center, double radius) {
  BvhBox b;
  for (int k = 0; k < 3; ++k) {
    b.lower[k] = std::nextafter(static_cast<float>(center[k] - radius), -INFINITY);
    b.upper[k] = std::nextafter(static_cast<float>(center[k] + radius), INFINITY);
  }
  return b;
}

uint32_t push_bvh_node(Bvh& bvh, const BvhBox& box) {
  BvhBinaryNode n{};
  for (int k = 0; k < 3; ++k) {
    n.lower[k] = box.lower[k];
    n.upper[k] = box.upper[k];
  }
  bvh.binary.push_back(n);
  return static_cast<uint32_t>(bvh.binary.size() - 1);
}

void make_bvh_leaf(Bvh& bvh, uint32_t node, const BvhPrimitive* begin, const BvhPrimitive* end) {
  const bool spheres = begin->kind == PrimitiveKind::Sphere;
  std::vector<uint32_t>& order = spheres ? bvh.sphere_order : bvh.triangle_order;
  bvh.binary[node].first = static_cast<uint32_t>(order.size());
  bvh.binary[node].count = static_cast<uint32_t>(end - begin) | (spheres ? CLPT_BVH_SPHERE_LEAF : 0u);
  for (const BvhPrimitive* p = begin; p != end; ++p) order.push_back(p->index);
}

void note_bvh_depth(Bvh& bvh, int depth) {
  bvh.binary_depth = std::max(bvh.binary_depth, depth);
  if (depth > CLPT_BVH_STACK)
    throw Error(ExitCode::BadScene, "the bounding volume hierarchy would be deeper than the kernels' traversal "
                                    "stack of " + std::to_string(CLPT_BVH_STACK) + " levels");
}

namespace {

// The collapse (collapse_bvh): one 4-wide node per call, appended before its interior children.
struct Collapser {
  const std::vector<BvhBinaryNode>& binary;
  std::vector<GpuBvhNode>& wide;
  int depth = 0;

  static double area(const BvhBinaryNode& n) {
    const double x = double(n.upper[0]) - n.lower[0], y = double(n.upper[1]) - n.lower[1],
                 z = double(n.upper[2]) - n.lower[2];
    return x < 0 ? 0 : x * y + y * z + z * x;
  }

  // Writes the 4-wide node for binary interior node `b` (or, for a tree that is one leaf, the
  // root holding that leaf) at wide depth `level` (root 1); returns its stack need.
  int collapse(uint32_t b, int level, uint32_t& index_out) {
    depth = std::max(depth, level);
    uint32_t slot[CLPT_BVH_WIDTH];
    int n = 0;
    if (binary[b].count != 0u) {
      slot[n++] = b;
    } else {
      slot[n++] = b + 1;
      slot[n++] = binary[b].first;
      while (n < CLPT_BVH_WIDTH) {
        int open = -1;
        for (int i = 0; i < n; ++i)
          if (binary[slot[i]].count == 0u && (open < 0 || area(binary[slot[i]]) > area(binary[slot[open]]))) open = i;
        if (open < 0) break;
        // Its two children take its place, in order.
        const uint32_t opened = slot[open];
        for (int i = n; i > open + 1; --i) slot[i] = slot[i - 1];
        slot[open] = opened + 1;
        slot[open + 1] = binary[opened].first;
        ++n;
      }
    }
    const uint32_t index = static_cast<uint32_t>(wide.size());
    index_out = index;
    wide.emplace_back();
    {
      GpuBvhNode& w = wide.back();
      for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
        w.lower_x[i] = w.lower_y[i] = w.lower_z[i] = INFINITY;  // an empty slot: inverted, never hit
        w.upper_x[i] = w.upper_y[i] = w.upper_z[i] = -INFINITY;
        w.child[i] = 0;
        w.count[i] = 0;
      }
      for (int i = 0; i < n; ++i) {
        const BvhBinaryNode& c = binary[slot[i]];
        w.lower_x[i] = c.lower[0];
        w.lower_y[i] = c.lower[1];
        w.lower_z[i] = c.lower[2];
        w.upper_x[i] = c.upper[0];
        w.upper_y[i] = c.upper[1];
        w.upper_z[i] = c.upper[2];
        w.count[i] = c.count;
        w.child[i] = c.count != 0u ? c.first : 0u;
      }
    }
    int deepest_child = 0;
    for (int i = 0; i < n; ++i) {
      if (binary[slot[i]].count != 0u) continue;
      uint32_t child = 0;
      deepest_child = std::max(deepest_child, collapse(slot[i], level + 1, child));
      wide[index].child[i] = child;  // `wide` may have moved: indexed again
    }
    return n - 1 + deepest_child;
  }
};

}  // namespace

void collapse_bvh(Bvh& bvh) {
  bvh.nodes.clear();
  bvh.depth = 0;
  bvh.stack_need = 0;
  if (!bvh.binary.empty()) {
    bvh.nodes.reserve(bvh.binary.size() / 2 + 1);
    Collapser c{bvh.binary, bvh.nodes};
    uint32_t root = 0;
    bvh.stack_need = c.collapse(0, 1, root);
    bvh.depth = c.depth;
  }
  std::vector<BvhBinaryNode>().swap(bvh.binary);
  if (bvh.stack_need > CLPT_BVH_STACK)
    throw Error(ExitCode::BadScene, "the bounding volume hierarchy could need " + std::to_string(bvh.stack_need) +
                                        " entries of the kernels' traversal stack, which holds " +
                                        std::to_string(CLPT_BVH_STACK));
}

namespace {

// Below this many primitives a subtree is built on the thread that reached it: spawning costs
// more than the build of a few thousand primitives.
constexpr size_t kParallelSubtree = 4096;
// At or above this many primitives a node's binning pass is split over the spare threads.
constexpr size_t kParallelBinning = 65536;

// BvhBox::grow, inlined into the build's inner loops (as a call it was a third of the build's
// instructions).
inline void grow_into(BvhBox& a, const BvhBox& b) {
  a.lower[0] = b.lower[0] < a.lower[0] ? b.lower[0] : a.lower[0];
  a.lower[1] = b.lower[1] < a.lower[1] ? b.lower[1] : a.lower[1];
  a.lower[2] = b.lower[2] < a.lower[2] ? b.lower[2] : a.lower[2];
  a.upper[0] = b.upper[0] > a.upper[0] ? b.upper[0] : a.upper[0];
  a.upper[1] = b.upper[1] > a.upper[1] ? b.upper[1] : a.upper[1];
  a.upper[2] = b.upper[2] > a.upper[2] ? b.upper[2] : a.upper[2];
}

inline void grow_into(BvhBox& a, const std::array<float, 3>& p) {
  a.lower[0] = p[0] < a.lower[0] ? p[0] : a.lower[0];
  a.lower[1] = p[1] < a.lower[1] ? p[1] : a.lower[1];
  a.lower[2] = p[2] < a.lower[2] ? p[2] : a.lower[2];
  a.upper[0] = p[0] > a.upper[0] ? p[0] : a.upper[0];
  a.upper[1] = p[1] > a.upper[1] ? p[1] : a.upper[1];
  a.upper[2] = p[2] > a.upper[2] ? p[2] : a.upper[2];
}

// One axis' bins: the primitives' boxes and counts.
struct Bins {
  std::array<BvhBox, 32> box;
  std::array<size_t, 32> count{};
  void reset(int bins) {
    for (int b = 0; b < bins; ++b) {
      box[size_t(b)] = BvhBox();
      count[size_t(b)] = 0;
    }
  }
};

// Which bin of `bins` along `axis` a centroid falls in.
struct Binning {
  std::array<double, 3> lo{}, extent{};  // of the centroids' box; an axis of extent 0 is not binned
  int bins = 16;
  int bin(const std::array<float, 3>& c, int axis) const {
    return std::min(bins - 1, static_cast<int>((c[axis] - lo[axis]) / extent[axis] * bins));
  }
};

// The threads a build may still start: a shared count, taken when a thread starts and given back
// when it ends. Which subtrees get threads then depends on timing, the hierarchy does not: every
// node is split by the same serial rule, and stitch() lays subtrees out as the serial build does.
struct ThreadBudget {
  std::atomic<int> spare{0};
  bool take() {
    int n = spare.load();
    while (n > 0)
      if (spare.compare_exchange_weak(n, n - 1)) return true;
    return false;
  }
  void give_back() { ++spare; }
};

struct Builder {
  const BvhBuildOptions& options;
  std::vector<BvhPrimitive> prims;  // reordered in place as ranges are split
  std::vector<std::array<float, 3>> centroids;
  ThreadBudget threads;

  std::array<float, 3> centroid(const BvhPrimitive& p) const {
    return {0.5f * (p.box.lower[0] + p.box.upper[0]), 0.5f * (p.box.lower[1] + p.box.upper[1]),
            0.5f * (p.box.lower[2] + p.box.upper[2])};
  }

  // Bins [begin, end) along all three axes at once. Neighbouring primitives tend to fall in the
  // same bin, whose box each then grows after the other: two sets of bins taken in turn break
  // that chain, and are merged after (min and max are exact, so the bins are the same).
  void bin_range(size_t begin, size_t end, const Binning& binning, std::array<Bins, 3>& out) const {
    auto bin_one = [&](size_t i, std::array<Bins, 3>& bins) {
      for (int axis = 0; axis < 3; ++axis) {
        if (!(binning.extent[axis] > 0)) continue;
        const int b = binning.bin(centroids[i], axis);
        grow_into(bins[size_t(axis)].box[size_t(b)], prims[i].box);
        ++bins[size_t(axis)].count[size_t(b)];
      }
    };
    if (end - begin < 256) {
      for (size_t i = begin; i < end; ++i) bin_one(i, out);
      return;
    }
    std::array<Bins, 3> odd;
    size_t i = begin;
    for (; i + 1 < end; i += 2) {
      bin_one(i, out);
      bin_one(i + 1, odd);
    }
    if (i < end) bin_one(i, out);
    for (int axis = 0; axis < 3; ++axis)
      for (int b = 0; b < binning.bins; ++b) {
        grow_into(out[size_t(axis)].box[size_t(b)], odd[size_t(axis)].box[size_t(b)]);
        out[size_t(axis)].count[size_t(b)] += odd[size_t(axis)].count[size_t(b)];
      }
  }

  // The bins of [begin, end): a large range in parallel slices whose bins are merged in slice
  // order (boxes by min/max and counts by sums: exact, so the same bins for any thread count).
  void bins_of(size_t begin, size_t end, const Binning& binning, std::array<Bins, 3>& out) {
    for (Bins& b : out) b.reset(binning.bins);
    const size_t count = end - begin;
    std::vector<std::thread> workers;
    std::vector<std::array<Bins, 3>> parts;
    if (count >= kParallelBinning) {
      int extra = 0;
      while (extra < 7 && threads.take()) ++extra;
      parts.resize(size_t(extra));
      const size_t slice = count / size_t(extra + 1);
      for (int t = 0; t < extra; ++t) {
        const size_t b = begin + slice * size_t(t + 1), e = t + 1 == extra ? end : b + slice;
        workers.emplace_back([this, b, e, &binning, &parts, t] { bin_range(b, e, binning, parts[size_t(t)]); });
      }
      end = begin + (extra > 0 ? slice : count);
    }
    bin_range(begin, end, binning, out);
    for (size_t t = 0; t < workers.size(); ++t) {
      workers[t].join();
      threads.give_back();
      for (int axis = 0; axis < 3; ++axis)
        for (int b = 0; b < binning.bins; ++b) {
          grow_into(out[axis].box[size_t(b)], parts[t][axis].box[size_t(b)]);
          out[axis].count[size_t(b)] += parts[t][axis].count[size_t(b)];
        }
    }
  }

  // The SAH's cost of testing n primitives: one per group of options.leaf_group.
  double leaf_cost(size_t n) const {
    const size_t group = size_t(options.leaf_group);
    return double((n + group - 1) / group);
  }

  // The best binned split of [begin, end) of box `box`: returns the position of the first
  // primitive of the right side after partitioning, or `begin` when no split beats a leaf (or none
  // exists); sets the two sides' boxes when it splits by the SAH.
  // `centre_box` is the box of the range's centroids; the sides' centroid boxes are set with theirs.
  size_t split(size_t begin, size_t end, const BvhBox& box, const BvhBox& centre_box, BvhBox& left_box,
               BvhBox& right_box, BvhBox& left_centres, BvhBox& right_centres) {
    const size_t count = end - begin;
    const int bins = options.bins;
    Binning binning;
    binning.bins = bins;
    for (int axis = 0; axis < 3; ++axis) {
      binning.lo[axis] = centre_box.lower[axis];
      binning.extent[axis] = double(centre_box.upper[axis]) - binning.lo[axis];
    }
    // Each thread's scratch bins (a split is decided before its sides are built).
    static thread_local std::array<Bins, 3> all;
    bins_of(begin, end, binning, all);
    double best_cost = INFINITY;
    int best_axis = -1, best_plane = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(binning.extent[axis] > 0)) continue;
      const Bins& bin = all[size_t(axis)];
      // Sweep from the right for the right sides' areas and counts, then from the left.
      std::array<double, 32> right_cost{};
      BvhBox right;
      size_t right_n = 0;
      // An empty bin changes neither side: its plane's side cost is its neighbour's, unrecomputed.
      double side_cost = 0;
      for (int b = bins - 1; b > 0; --b) {
        if (bin.count[size_t(b)] > 0) {
          grow_into(right, bin.box[size_t(b)]);
          right_n += bin.count[size_t(b)];
          side_cost = right.half_area() * leaf_cost(right_n);
        }
        right_cost[size_t(b)] = side_cost;
      }
      BvhBox left;
      size_t left_n = 0;
      side_cost = 0;
      for (int plane = 1; plane < bins; ++plane) {
        if (bin.count[size_t(plane - 1)] > 0) {
          grow_into(left, bin.box[size_t(plane - 1)]);
          left_n += bin.count[size_t(plane - 1)];
          side_cost = left.half_area() * leaf_cost(left_n);
        }
        if (left_n == 0 || left_n == count) continue;
        const double cost = side_cost + right_cost[size_t(plane)];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_plane = plane;
        }
      }
    }
    const double area = box.half_area();
    const double split_cost = options.traversal_cost + (area > 0 ? best_cost / area : INFINITY);
    const bool leaf_ok = count <= static_cast<size_t>(options.max_leaf);
    if (best_axis < 0 || (leaf_ok && split_cost >= leaf_cost(count))) {
      if (leaf_ok || count < 2) return begin;
      // Coincident centroids: halve by index so the recursion ends.
      const size_t mid = begin + count / 2;
      left_box = bounds(begin, mid);
      right_box = bounds(mid, end);
      left_centres = centre_bounds(begin, mid);
      right_centres = centre_bounds(mid, end);
      return mid;
    }
    left_box = BvhBox();
    right_box = BvhBox();
    const Bins& bin = all[size_t(best_axis)];
    for (int b = 0; b < bins; ++b) grow_into(b < best_plane ? left_box : right_box, bin.box[size_t(b)]);
    left_centres = BvhBox();
    right_centres = BvhBox();
    size_t mid = begin;
    for (size_t i = begin; i < end; ++i) {
      if (binning.bin(centroids[i], best_axis) < best_plane) {
        grow_into(left_centres, centroids[i]);
        std::swap(prims[i], prims[mid]);
        std::swap(centroids[i], centroids[mid]);
        ++mid;
      } else {
        grow_into(right_centres, centroids[i]);
      }
    }
    return mid;
  }

  BvhBox bounds(size_t begin, size_t end) const {
    BvhBox b;
    for (size_t i = begin; i < end; ++i) grow_into(b, prims[i].box);
    return b;
  }

  BvhBox centre_bounds(size_t begin, size_t end) const {
    BvhBox b;
    for (size_t i = begin; i < end; ++i) grow_into(b, centroids[i]);
    return b;
  }

  // Appends `sub` (a subtree built on its own, indices from 0) to `out` as the serial build lays
  // it out right after what `out` holds.
  static void stitch(Bvh& out, const Bvh& sub) {
    const uint32_t node_base = static_cast<uint32_t>(out.binary.size());
    const uint32_t triangle_base = static_cast<uint32_t>(out.triangle_order.size());
    const uint32_t sphere_base = static_cast<uint32_t>(out.sphere_order.size());
    for (BvhBinaryNode n : sub.binary) {
      if (n.count == 0u)
        n.first += node_base;
      else
        n.first += (n.count & CLPT_BVH_SPHERE_LEAF) ? sphere_base : triangle_base;
      out.binary.push_back(n);
    }
    out.triangle_order.insert(out.triangle_order.end(), sub.triangle_order.begin(), sub.triangle_order.end());
    out.sphere_order.insert(out.sphere_order.end(), sub.sphere_order.begin(), sub.sphere_order.end());
    out.binary_depth = std::max(out.binary_depth, sub.binary_depth);
  }

  // The subtree over [begin, end) (box `box`, centroids' box `centres`) at `depth`, appended to
  // `out` depth first.
  void build(size_t begin, size_t end, int depth, const BvhBox& box, const BvhBox& centres, Bvh& out) {
    note_bvh_depth(out, depth);
    const uint32_t node = push_bvh_node(out, box);
    if (end - begin == 1) {  // no split exists: split() would say so after binning
      make_bvh_leaf(out, node, prims.data() + begin, prims.data() + end);
      return;
    }
    BvhBox left_box, right_box, left_centres, right_centres;
    size_t mid = split(begin, end, box, centres, left_box, right_box, left_centres, right_centres);
    if (mid == begin) {
      // A leaf, unless it would mix kinds: then spheres and triangles become two leaves.
      const auto sphere_first = std::stable_partition(prims.begin() + begin, prims.begin() + end,
                                                      [](const BvhPrimitive& p) { return p.kind == PrimitiveKind::Sphere; });
      mid = static_cast<size_t>(sphere_first - prims.begin());
      if (mid == begin || mid == end) {
        make_bvh_leaf(out, node, prims.data() + begin, prims.data() + end);
        return;
      }
      for (size_t i = begin; i < end; ++i) centroids[i] = centroid(prims[i]);
      left_box = bounds(begin, mid);
      right_box = bounds(mid, end);
      left_centres = centre_bounds(begin, mid);
      right_centres = centre_bounds(mid, end);
    }
    // The right side on a thread of its own when it is large and one is spare.
    if (end - mid >= kParallelSubtree && mid - begin >= kParallelSubtree && threads.take()) {
      Bvh right;
      std::exception_ptr failed;
      std::thread worker([&] {
        try {
          build(mid, end, depth + 1, right_box, right_centres, right);
        } catch (...) {
          failed = std::current_exception();
        }
      });
      try {
        build(begin, mid, depth + 1, left_box, left_centres, out);
      } catch (...) {
        worker.join();
        threads.give_back();
        throw;
      }
      worker.join();
      threads.give_back();
      if (failed) std::rethrow_exception(failed);
      out.binary[node].first = static_cast<uint32_t>(out.binary.size());
      out.binary[node].count = 0;
      stitch(out, right);
      return;
    }
    build(begin, mid, depth + 1, left_box, left_centres, out);
    out.binary[node].first = static_cast<uint32_t>(out.binary.size());
    out.binary[node].count = 0;
    build(mid, end, depth + 1, right_box, right_centres, out);
  }
};

}  // namespace

int bvh_build_threads(const BvhBuildOptions& options) {
  if (options.threads > 0) return options.threads;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

Bvh build_bvh(const std::vector<BvhPrimitive>& primitives, const BvhBuildOptions& options) {
  const auto start = Clock::now();
  const double cpu_start = process_cpu_seconds();
  if (options.bins < 2 || options.bins > 32)
    throw Error(ExitCode::Failure, "build_bvh: bins must be 2 to 32, not " + std::to_string(options.bins));
  if (options.leaf_group < 1 || options.leaf_group > options.max_leaf)
    throw Error(ExitCode::Failure, "build_bvh: leaf_group must be 1 to max_leaf, not " + std::to_string(options.leaf_group));
  Builder b{options, primitives, {}, {}};
  b.threads.spare = bvh_build_threads(options) - 1;
  Bvh out;
  if (!primitives.empty()) {
    b.centroids.reserve(primitives.size());
    for (const BvhPrimitive& p : b.prims) b.centroids.push_back(b.centroid(p));
    out.binary.reserve(2 * primitives.size());
    b.build(0, primitives.size(), 1, b.bounds(0, primitives.size()), b.centre_bounds(0, primitives.size()), out);
  }
  collapse_bvh(out);
  out.build_seconds = seconds_since(start);
  out.build_cpu_seconds = process_cpu_seconds() - cpu_start;
  out.build_threads = bvh_build_threads(options);
  out.leaf_group = options.leaf_group;
  return out;
}

}  // namespace clpt
