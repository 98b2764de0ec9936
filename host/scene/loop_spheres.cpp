#include "scene/loop_spheres.h"

#include <algorithm>

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

int loop_triangle_count(const Scene& scene) {
  if (spheres_in_hierarchy(scene)) return 0;
  size_t n = 0;
  for (const TriangleMesh& m : scene.meshes) n += m.triangles.size();
  return n <= static_cast<size_t>(kMaxLoopTriangles) ? static_cast<int>(n) : 0;
}

}  // namespace clpt
