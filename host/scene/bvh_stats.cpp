// The hierarchy's statistics (bvh_stats.h): SAH cost, and the replica of the kernels' traversal
// order in double over a deterministic ray sample.
#include "scene/bvh_stats.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace clpt {
namespace {

using D3 = std::array<double, 3>;

D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
D3 add_scaled(const D3& a, const D3& b, double s) { return {a[0] + b[0] * s, a[1] + b[1] * s, a[2] + b[2] * s}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
D3 normalized(const D3& a) {
  const double n = std::sqrt(dot(a, a));
  return n > 0 ? D3{a[0] / n, a[1] / n, a[2] / n} : a;
}
D3 load(const float v[3]) { return {v[0], v[1], v[2]}; }
D3 load(const float v[3], const float lo[3]) {
  return {double(v[0]) + lo[0], double(v[1]) + lo[1], double(v[2]) + lo[2]};
}

constexpr double kNoHit = std::numeric_limits<double>::infinity();

double half_area(double lx, double ly, double lz, double ux, double uy, double uz) {
  const double x = ux - lx, y = uy - ly, z = uz - lz;
  return x < 0 ? 0 : x * y + y * z + z * x;
}

// Child slot i's box of a node: its half area (0 for an empty slot).
double slot_half_area(const GpuBvhNode& n, int i) {
  return half_area(n.lower_x[i], n.lower_y[i], n.lower_z[i], n.upper_x[i], n.upper_y[i], n.upper_z[i]);
}

bool slot_used(const GpuBvhNode& n, int i) { return n.lower_x[i] <= n.upper_x[i]; }

// The half area of a node's own box: the union of its children's.
double node_half_area(const GpuBvhNode& n) {
  double lo[3] = {kNoHit, kNoHit, kNoHit}, hi[3] = {-kNoHit, -kNoHit, -kNoHit};
  for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
    if (!slot_used(n, i)) continue;
    lo[0] = std::min(lo[0], double(n.lower_x[i]));
    lo[1] = std::min(lo[1], double(n.lower_y[i]));
    lo[2] = std::min(lo[2], double(n.lower_z[i]));
    hi[0] = std::max(hi[0], double(n.upper_x[i]));
    hi[1] = std::max(hi[1], double(n.upper_y[i]));
    hi[2] = std::max(hi[2], double(n.upper_z[i]));
  }
  return half_area(lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
}

// bvh_node_entries / bvh_slot_entry (kernels/bvh.cl) for slot i, in double: the entry distance,
// or kNoHit. Near planes picked by the direction's signs, as there (an empty slot never hits).
double slot_entry(const GpuBvhNode& n, int i, const D3& o, const D3& inv, double t_max) {
  const float* lower[3] = {n.lower_x, n.lower_y, n.lower_z};
  const float* upper[3] = {n.upper_x, n.upper_y, n.upper_z};
  double t_near = 0, t_far = kNoHit;
  for (size_t k = 0; k < 3; ++k) {
    const bool negative = inv[k] < 0;
    const double a = (double((negative ? upper : lower)[k][i]) - o[k]) * inv[k];
    const double b = (double((negative ? lower : upper)[k][i]) - o[k]) * inv[k];
    t_near = std::max(t_near, a);
    t_far = std::min(t_far, b);
  }
  t_far *= 1.0000004;  // the kernels' 1 + 2 gamma(3)
  return t_near <= t_far && t_near < t_max ? t_near : kNoHit;
}

// The nearest t > t_min where the ray meets the sphere (s0, n0, r as stored: centre s0 - r n0).
double sphere_hit(const GpuSphere& s, const D3& o, const D3& d, double t_min) {
  const double r = double(s.radius) + s.radius_lo;
  const D3 centre = add_scaled(load(s.surface_point, s.surface_point_lo), load(s.surface_normal, s.surface_normal_lo), -r);
  const D3 oc = sub(o, centre);
  const double a = dot(d, d), b = dot(oc, d), c = dot(oc, oc) - r * r;
  const double disc = b * b - a * c;
  if (disc < 0) return kNoHit;
  const double root = std::sqrt(disc);
  const double t0 = (-b - root) / a, t1 = (-b + root) / a;
  if (t0 > t_min) return t0;
  if (t1 > t_min) return t1;
  return kNoHit;
}

// The distance t > 0 where the ray meets the triangle, in double (Moller-Trumbore; the replica
// needs the same hits as the kernels' watertight test, not its edge rule).
double triangle_hit(const GpuTriangle& tri, const D3& o, const D3& d) {
  const D3 v0 = load(tri.v0), e1 = sub(load(tri.v1), v0), e2 = sub(load(tri.v2), v0);
  const D3 p = cross(d, e2);
  const double det = dot(e1, p);
  if (det == 0) return kNoHit;
  const double inv = 1 / det;
  const D3 s = sub(o, v0);
  const double u = dot(s, p) * inv;
  if (u < 0 || u > 1) return kNoHit;
  const D3 q = cross(s, e1);
  const double v = dot(d, q) * inv;
  if (v < 0 || u + v > 1) return kNoHit;
  const double t = dot(e2, q) * inv;
  return t > 0 ? t : kNoHit;
}

// The kernels' inverse_direction: a zero component becomes 1/(+-1e-30).
D3 inverse_direction(const D3& d) {
  D3 inv;
  for (size_t k = 0; k < 3; ++k) {
    const double tiny = double(1e-30f);
    inv[k] = 1 / (std::fabs(d[k]) > tiny ? d[k] : std::copysign(tiny, d[k]));
  }
  return inv;
}

uint64_t splitmix64(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

double unit_double(uint64_t bits) { return double(bits >> 11) * 0x1.0p-53; }

// The geometric unit normal at a hit, and the hit point.
D3 hit_normal(const DeviceScene& ds, const StatsHit& h, const D3& p) {
  if (h.triangle >= 0) {
    const GpuTriangle& t = ds.triangles[size_t(h.triangle)];
    return normalized(cross(sub(load(t.v1), load(t.v0)), sub(load(t.v2), load(t.v0))));
  }
  const GpuSphere& s = ds.spheres[size_t(h.sphere)];
  const double r = double(s.radius) + s.radius_lo;
  const D3 centre = add_scaled(load(s.surface_point, s.surface_point_lo), load(s.surface_normal, s.surface_normal_lo), -r);
  return normalized(sub(p, centre));
}

}  // namespace

double bvh_sah_cost(const Bvh& bvh, double traversal_cost) {
  if (bvh.nodes.empty()) return 0;
  const double root = node_half_area(bvh.nodes.front());
  if (!(root > 0)) return 0;
  const uint32_t group = uint32_t(std::max(bvh.leaf_group, 1));
  double cost = 0;
  for (const GpuBvhNode& n : bvh.nodes) {
    cost += traversal_cost * node_half_area(n) / root;
    for (int i = 0; i < CLPT_BVH_WIDTH; ++i)
      if (n.count[i] != 0u) {
        const uint32_t tests = ((n.count[i] & CLPT_BVH_COUNT_MASK) + group - 1u) / group;
        cost += double(tests) * slot_half_area(n, i) / root;
      }
  }
  return cost;
}

void TraversalCounts::add(const TraversalCounts& o) {
  rays += o.rays;
  hits += o.hits;
  nodes += o.nodes;
  boxes += o.boxes;
  triangles += o.triangles;
  hierarchy_spheres += o.hierarchy_spheres;
  loop_spheres += o.loop_spheres;
  loop_triangles += o.loop_triangles;
}

TraversalCounts TraversalStats::all() const {
  TraversalCounts c = camera;
  c.add(bounce);
  return c;
}

StatsHit replica_closest_hit(const DeviceScene& ds, const StatsRay& ray, TraversalCounts& counts,
                             bool triangle_loop) {
  const D3& o = ray.origin;
  const D3& d = ray.direction;
  StatsHit hit;
  hit.t = kNoHit;
  ++counts.rays;
  // scene_loop_hit: the loop's spheres first.
  for (uint32_t i = 0; i < ds.loop_spheres; ++i) {
    ++counts.loop_spheres;
    const double t = sphere_hit(ds.spheres[i], o, d, ray.t_min);
    if (t < hit.t) {
      hit.t = t;
      hit.sphere = int(i);
    }
  }
  // triangle_loop_hit: the loop's triangles (the first ones), where the kernel tests them so.
  const bool loop_first = triangle_loop && ds.loop_triangles > 0;
  for (uint32_t i = 0; loop_first && i < ds.loop_triangles; ++i) {
    ++counts.loop_triangles;
    const double t = triangle_hit(ds.triangles[i], o, d);
    if (t < hit.t) {
      hit.t = t;
      hit.sphere = -1;
      hit.triangle = int(i);
    }
  }
  // bvh_traverse, closest hit, from CLPT_BVH_ROOT.
  const std::vector<GpuBvhNode>& nodes = ds.bvh.nodes;
  if (!nodes.empty()) {
    const D3 inv = inverse_direction(d);
    uint32_t stack[CLPT_BVH_STACK];
    uint32_t depth = 0, node = loop_first ? 1 : 0, ref = 0;
    bool open = true, done = false;
    while (!done) {
      ++counts.nodes;
      bool leaf = false;
      uint32_t first = 0, count = 0;
      if (open) {
        const GpuBvhNode& n = nodes[node];
        std::array<std::pair<double, uint32_t>, CLPT_BVH_WIDTH> t;
        for (int i = 0; i < CLPT_BVH_WIDTH; ++i) {
          counts.boxes += slot_used(n, i) ? 1 : 0;
          t[size_t(i)] = {slot_entry(n, i, o, inv, hit.t), uint32_t(i)};
        }
        // Nearest first, as the kernels' sorting network (ties in either order: the same set is
        // visited, and the counts differ only for rays with two children at one distance).
        std::stable_sort(t.begin(), t.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        for (int k = CLPT_BVH_WIDTH - 1; k >= 1; --k)
          if (t[size_t(k)].first < kNoHit) stack[depth++] = node << 2 | t[size_t(k)].second;
        if (t[0].first < kNoHit) {
          count = n.count[t[0].second];
          first = n.child[t[0].second];
          leaf = count != 0;
          node = first;
          open = !leaf;
        } else {
          open = false;
        }
      } else {
        const GpuBvhNode& n = nodes[ref >> 2];
        const int slot = int(ref & 3u);
        ++counts.boxes;
        if (slot_entry(n, slot, o, inv, hit.t) < kNoHit) {  // else: behind a nearer hit found since
          count = n.count[slot];
          first = n.child[slot];
          leaf = count != 0;
          node = first;
          open = !leaf;
        }
      }
      if (leaf) {
        const uint32_t n_prims = count & CLPT_BVH_COUNT_MASK;
        if (count & CLPT_BVH_SPHERE_LEAF) {
          for (uint32_t i = first; i < first + n_prims; ++i) {
            ++counts.hierarchy_spheres;
            const double t = sphere_hit(ds.spheres[i], o, d, ray.t_min);  // the sphere buffer's index
            if (t < hit.t) {
              hit.t = t;
              hit.sphere = int(i);
              hit.triangle = -1;
            }
          }
        } else {
          for (uint32_t i = first; i < first + n_prims; ++i) {
            ++counts.triangles;
            const double t = triangle_hit(ds.triangles[i], o, d);
            if (t < hit.t) {
              hit.t = t;
              hit.sphere = -1;
              hit.triangle = int(i);
            }
          }
        }
      }
      if (!open) {
        done = depth == 0;
        ref = done ? 0 : stack[--depth];
      }
    }
  }
  if (hit.hit()) ++counts.hits;
  return hit;
}

StatsRaySample stats_rays(const DeviceScene& ds, int width, int height, size_t max_camera_rays) {
  StatsRaySample sample;
  const double pixels = double(width) * double(height);
  const int stride = std::max(1, int(std::ceil(std::sqrt(pixels / double(std::max<size_t>(max_camera_rays, 1))) - 1e-9)));
  const GpuCamera& cam = ds.camera;
  const bool ortho = cam.projection == CLPT_PROJECTION_ORTHOGRAPHIC;
  for (int row = stride / 2; row < height; row += stride)
    for (int col = stride / 2; col < width; col += stride) {
      // camera_ray (kernels/camera.cl) through the pixel's centre.
      const double fx = (col + 0.5) / width, fy = ((height - 1 - row) + 0.5) / height;
      D3 on_sensor = add_scaled(add_scaled(D3{0, 0, 0}, load(cam.sensor_right), fx - 0.5), load(cam.sensor_up), fy - 0.5);
      StatsRay r;
      r.t_min = ds.ray_epsilon;
      if (ortho) {
        r.origin = on_sensor;
        r.direction = normalized(load(cam.sensor_center));
      } else {
        r.direction = normalized(add_scaled(on_sensor, load(cam.sensor_center), 1.0));
      }
      sample.rays.push_back(r);
    }
  sample.camera_rays = sample.rays.size();
  for (size_t i = 0; i < sample.camera_rays; ++i) {
    const StatsRay camera_ray = sample.rays[i];
    TraversalCounts ignored;
    const StatsHit h = replica_closest_hit(ds, camera_ray, ignored);
    if (!h.hit()) continue;
    const D3 p = add_scaled(camera_ray.origin, camera_ray.direction, h.t);
    D3 n = hit_normal(ds, h, p);
    if (dot(n, camera_ray.direction) > 0) n = {-n[0], -n[1], -n[2]};
    // A frame about n and a cosine-distributed direction (Malley's method).
    const D3 helper = std::fabs(n[0]) > 0.9 ? D3{0, 1, 0} : D3{1, 0, 0};
    const D3 t1 = normalized(cross(helper, n)), t2 = cross(n, t1);
    const uint64_t bits = splitmix64(uint64_t(i));
    const double u0 = unit_double(bits), u1 = unit_double(splitmix64(bits));
    const double radius = std::sqrt(u0), phi = 2 * M_PI * u1;
    const double x = radius * std::cos(phi), y = radius * std::sin(phi), z = std::sqrt(std::max(0.0, 1 - u0));
    StatsRay b;
    b.t_min = ds.ray_epsilon;
    b.origin = add_scaled(p, n, double(ds.ray_epsilon));
    b.direction = normalized(add_scaled(add_scaled(D3{n[0] * z, n[1] * z, n[2] * z}, t1, x), t2, y));
    sample.rays.push_back(b);
  }
  return sample;
}

TraversalStats measure_traversal(const DeviceScene& ds, const StatsRaySample& sample, bool triangle_loop) {
  TraversalStats stats;
  for (size_t i = 0; i < sample.rays.size(); ++i)
    replica_closest_hit(ds, sample.rays[i], i < sample.camera_rays ? stats.camera : stats.bounce, triangle_loop);
  return stats;
}

}  // namespace clpt
