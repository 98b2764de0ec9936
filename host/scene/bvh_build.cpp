// Binned SAH construction of the kernels' hierarchy (bvh_build.h). Top down: at each node the
// primitives' centroids are binned along each axis, the plane with the least SAH cost
// (traversal_cost + (A_left N_left + A_right N_right) / A) wins against making a leaf (cost N),
// and the two sides are built recursively; the node array is filled depth first as it goes.
#include "scene/bvh_build.h"

#include <algorithm>
#include <cmath>
#include <string>

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
  GpuBvhNode n{};
  for (int k = 0; k < 3; ++k) {
    n.lower[k] = box.lower[k];
    n.upper[k] = box.upper[k];
  }
  bvh.nodes.push_back(n);
  return static_cast<uint32_t>(bvh.nodes.size() - 1);
}

void make_bvh_leaf(Bvh& bvh, uint32_t node, const BvhPrimitive* begin, const BvhPrimitive* end) {
  const bool spheres = begin->kind == PrimitiveKind::Sphere;
  std::vector<uint32_t>& order = spheres ? bvh.sphere_order : bvh.triangle_order;
  bvh.nodes[node].first = static_cast<uint32_t>(order.size());
  bvh.nodes[node].count = static_cast<uint32_t>(end - begin) | (spheres ? CLPT_BVH_SPHERE_LEAF : 0u);
  for (const BvhPrimitive* p = begin; p != end; ++p) order.push_back(p->index);
}

void note_bvh_depth(Bvh& bvh, int depth) {
  bvh.depth = std::max(bvh.depth, depth);
  if (depth > CLPT_BVH_STACK)
    throw Error(ExitCode::BadScene, "the bounding volume hierarchy would be deeper than the kernels' traversal "
                                    "stack of " + std::to_string(CLPT_BVH_STACK) + " levels");
}

namespace {

struct Builder {
  const BvhBuildOptions& options;
  std::vector<BvhPrimitive> prims;  // reordered in place as ranges are split
  std::vector<std::array<float, 3>> centroids;
  Bvh out;

  std::array<float, 3> centroid(const BvhPrimitive& p) const {
    return {0.5f * (p.box.lower[0] + p.box.upper[0]), 0.5f * (p.box.lower[1] + p.box.upper[1]),
            0.5f * (p.box.lower[2] + p.box.upper[2])};
  }

  BvhBox bounds(size_t begin, size_t end) const {
    BvhBox b;
    for (size_t i = begin; i < end; ++i) b.grow(prims[i].box);
    return b;
  }

  uint32_t push_node(const BvhBox& box) { return push_bvh_node(out, box); }

  // A leaf over [begin, end), all of one kind.
  void make_leaf(uint32_t node, size_t begin, size_t end) {
    make_bvh_leaf(out, node, prims.data() + begin, prims.data() + end);
  }

  // The best binned split of [begin, end): returns the position of the first primitive of the
  // right side after partitioning, or `begin` when no split beats a leaf (or none exists).
  size_t split(size_t begin, size_t end, const BvhBox& box) {
    const size_t count = end - begin;
    BvhBox centre_box;
    for (size_t i = begin; i < end; ++i) centre_box.grow(centroids[i]);
    const int bins = options.bins;
    double best_cost = INFINITY;
    int best_axis = -1, best_plane = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const double lo = centre_box.lower[axis], extent = double(centre_box.upper[axis]) - lo;
      if (!(extent > 0)) continue;
      std::vector<BvhBox> bin_box(bins);
      std::vector<size_t> bin_count(bins, 0);
      for (size_t i = begin; i < end; ++i) {
        const int b = std::min(bins - 1, static_cast<int>((centroids[i][axis] - lo) / extent * bins));
        bin_box[b].grow(prims[i].box);
        ++bin_count[b];
      }
      // Sweep from the right for the right sides' areas and counts, then from the left.
      std::vector<double> right_cost(bins, 0);
      BvhBox right;
      size_t right_n = 0;
      for (int b = bins - 1; b > 0; --b) {
        right.grow(bin_box[b]);
        right_n += bin_count[b];
        right_cost[b] = right.half_area() * double(right_n);
      }
      BvhBox left;
      size_t left_n = 0;
      for (int plane = 1; plane < bins; ++plane) {
        left.grow(bin_box[plane - 1]);
        left_n += bin_count[plane - 1];
        if (left_n == 0 || left_n == count) continue;
        const double cost = left.half_area() * double(left_n) + right_cost[plane];
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
    if (best_axis < 0 || (leaf_ok && split_cost >= double(count))) {
      if (leaf_ok || count < 2) return begin;
      // Coincident centroids: halve by index so the recursion ends.
      return begin + count / 2;
    }
    const double lo = centre_box.lower[best_axis];
    const double extent = double(centre_box.upper[best_axis]) - lo;
    size_t mid = begin;
    for (size_t i = begin; i < end; ++i) {
      const int b = std::min(bins - 1, static_cast<int>((centroids[i][best_axis] - lo) / extent * bins));
      if (b < best_plane) {
        std::swap(prims[i], prims[mid]);
        std::swap(centroids[i], centroids[mid]);
        ++mid;
      }
    }
    return mid;
  }

  void build(size_t begin, size_t end, int depth) {
    note_bvh_depth(out, depth);
    const BvhBox box = bounds(begin, end);
    const uint32_t node = push_node(box);
    size_t mid = split(begin, end, box);
    if (mid == begin) {
      // A leaf, unless it would mix kinds: then spheres and triangles become two leaves.
      const auto sphere_first = std::stable_partition(prims.begin() + begin, prims.begin() + end,
                                                      [](const BvhPrimitive& p) { return p.kind == PrimitiveKind::Sphere; });
      mid = static_cast<size_t>(sphere_first - prims.begin());
      if (mid == begin || mid == end) {
        make_leaf(node, begin, end);
        return;
      }
      for (size_t i = begin; i < end; ++i) centroids[i] = centroid(prims[i]);
    }
    build(begin, mid, depth + 1);
    out.nodes[node].first = static_cast<uint32_t>(out.nodes.size());
    out.nodes[node].count = 0;
    build(mid, end, depth + 1);
  }
};

}  // namespace

Bvh build_bvh(const std::vector<BvhPrimitive>& primitives, const BvhBuildOptions& options) {
  const auto start = Clock::now();
  Builder b{options, primitives, {}, {}};
  if (!primitives.empty()) {
    b.centroids.reserve(primitives.size());
    for (const BvhPrimitive& p : b.prims) b.centroids.push_back(b.centroid(p));
    b.out.nodes.reserve(2 * primitives.size());
    b.build(0, primitives.size(), 1);
  }
  b.out.build_seconds = seconds_since(start);
  return std::move(b.out);
}

}  // namespace clpt
