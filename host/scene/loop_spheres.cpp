#include "scene/loop_spheres.h"

#include <algorithm>
#include <array>
#include <cstdint>

#include "scene/vec3_ops.h"

namespace clpt {

bool spheres_in_hierarchy(const Scene& scene) {
  return static_cast<int>(scene.spheres.size()) > kMaxLoopSpheres;
}

std::vector<bool> loop_spheres(const Scene& scene) {
  const size_t n = scene.spheres.size();
  if (!spheres_in_hierarchy(scene)) return std::vector<bool>(n, true);
  std::vector<double> radii;
  for (const Sphere& s : scene.spheres) radii.push_back(s.radius);
  std::nth_element(radii.begin(), radii.begin() + long(n / 2), radii.end());
  const double large = 10 * radii[n / 2];
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return scene.spheres[a].radius > scene.spheres[b].radius; });
  std::vector<bool> in_loop(n, false);
  for (size_t k = 0; k < std::min<size_t>(n, 8) && scene.spheres[order[k]].radius >= large; ++k) in_loop[order[k]] = true;
  return in_loop;
}

namespace {

// A triangle's area, world units^2.
double area(const TriangleMesh& m, const std::array<uint32_t, 3>& t) {
  return 0.5 * length(cross(sub(m.positions[t[1]], m.positions[t[0]]), sub(m.positions[t[2]], m.positions[t[0]])));
}

size_t triangle_total(const Scene& scene) {
  size_t n = 0;
  for (const TriangleMesh& m : scene.meshes) n += m.triangles.size();
  return n;
}

}  // namespace

std::vector<bool> loop_meshes(const Scene& scene) {
  const size_t meshes = scene.meshes.size();
  if (spheres_in_hierarchy(scene)) return std::vector<bool>(meshes, false);
  const size_t total = triangle_total(scene);
  if (total <= static_cast<size_t>(kMaxLoopTriangles)) {
    std::vector<bool> all(meshes);
    for (size_t i = 0; i < meshes; ++i) all[i] = !scene.meshes[i].triangles.empty();
    return all;
  }
  std::vector<double> areas;
  areas.reserve(total);
  std::vector<double> mean(meshes, 0.0);
  for (size_t i = 0; i < meshes; ++i) {
    for (const auto& t : scene.meshes[i].triangles) {
      areas.push_back(area(scene.meshes[i], t));
      mean[i] += areas.back();
    }
    if (!scene.meshes[i].triangles.empty()) mean[i] /= double(scene.meshes[i].triangles.size());
  }
  std::nth_element(areas.begin(), areas.begin() + long(total / 2), areas.end());
  const double large = 100 * areas[total / 2];
  std::vector<size_t> order;
  for (size_t i = 0; i < meshes; ++i)
    if (!scene.meshes[i].triangles.empty() && mean[i] >= large && mean[i] > 0) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return mean[a] > mean[b]; });
  std::vector<bool> in_loop(meshes, false);
  size_t room = kMaxLoopTriangles;
  for (size_t i : order) {
    const size_t n = scene.meshes[i].triangles.size();
    if (n > room) continue;
    in_loop[i] = true;
    room -= n;
  }
  return in_loop;
}

TriangleLoopChoice triangle_loop_choice(const Scene& scene) {
  TriangleLoopChoice c;
  c.meshes = loop_meshes(scene);
  size_t n = 0;
  for (size_t i = 0; i < c.meshes.size(); ++i) n += c.meshes[i] ? scene.meshes[i].triangles.size() : 0;
  c.triangles = static_cast<int>(n);
  c.hierarchy_triangles = triangle_total(scene) > n;
  return c;
}

int loop_triangle_count(const Scene& scene) { return triangle_loop_choice(scene).triangles; }

bool hierarchy_triangles(const Scene& scene) { return triangle_loop_choice(scene).hierarchy_triangles; }

}  // namespace clpt
