// Test meshes built in code (mesh_test_util.h).
#include "mesh_test_util.h"

#include <cmath>

namespace clpt::test {

TriangleMesh tessellated_sphere(const Vec3& center, double radius, int rings, int segments,
                                const Material& material, bool normals) {
  TriangleMesh m;
  m.name = "tessellated sphere";
  m.material = material;
  const double pi = 3.14159265358979323846;
  // Vertex 0 the north pole, then (rings - 1) rings of `segments`, then the south pole.
  auto add = [&](const Vec3& unit) {
    m.positions.push_back({center[0] + radius * unit[0], center[1] + radius * unit[1], center[2] + radius * unit[2]});
    if (normals) m.normals.push_back(unit);
  };
  add({0, 1, 0});
  for (int r = 1; r < rings; ++r) {
    const double theta = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2 * pi * s / segments;
      add({std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)});
    }
  }
  add({0, -1, 0});
  const uint32_t south = static_cast<uint32_t>(m.positions.size() - 1);
  auto ring_vertex = [&](int r, int s) { return static_cast<uint32_t>(1 + (r - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, ring_vertex(1, s), ring_vertex(1, s + 1)});
    m.triangles.push_back({south, ring_vertex(rings - 1, s + 1), ring_vertex(rings - 1, s)});
  }
  for (int r = 1; r + 1 < rings; ++r) {
    for (int s = 0; s < segments; ++s) {
      const uint32_t a = ring_vertex(r, s), b = ring_vertex(r, s + 1);
      const uint32_t c = ring_vertex(r + 1, s), d = ring_vertex(r + 1, s + 1);
      m.triangles.push_back({a, c, d});
      m.triangles.push_back({a, d, b});
    }
  }
  return m;
}

TriangleMesh closed_box(const Vec3& lo, const Vec3& hi, const Material& material) {
  TriangleMesh m;
  m.name = "closed box";
  m.material = material;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]});
  // Two triangles per face, counter-clockwise seen from outside.
  const uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& f : faces) {
    m.triangles.push_back({f[0], f[1], f[2]});
    m.triangles.push_back({f[0], f[2], f[3]});
  }
  return m;
}

TriangleMesh random_soup(std::mt19937& rng, int count, const Vec3& center, double extent, double size,
                         const Material& material) {
  TriangleMesh m;
  m.name = "random soup";
  m.material = material;
  std::uniform_real_distribution<double> u(-1, 1);
  for (int i = 0; i < count; ++i) {
    const Vec3 base = {center[0] + extent * u(rng), center[1] + extent * u(rng), center[2] + extent * u(rng)};
    for (int c = 0; c < 3; ++c)
      m.positions.push_back({base[0] + size * u(rng), base[1] + size * u(rng), base[2] + size * u(rng)});
    const uint32_t b = static_cast<uint32_t>(3 * i);
    m.triangles.push_back({b, b + 1, b + 2});
  }
  return m;
}

Scene cornell_box_with_ball(Scene scene) {
  std::vector<TriangleMesh> kept;
  for (const TriangleMesh& m : scene.meshes)
    if (m.name != "short_block" && m.name != "tall_block") kept.push_back(m);
  scene.meshes = kept;
  scene.meshes.push_back(tessellated_sphere({280, 120, 280}, 110, 16, 24, lambertian(0.6), true));
  return scene;
}

Material lambertian(double albedo) {
  Material m;
  m.type = MaterialType::Lambertian;
  m.reflectance = {albedo, albedo, albedo};
  return m;
}

Material emitter(double radiance) {
  Material m;
  m.type = MaterialType::Emitter;
  m.emission = {radiance, radiance, radiance};
  return m;
}

Material mirror(double reflectance) {
  Material m;
  m.type = MaterialType::Mirror;
  m.reflectance = {reflectance, reflectance, reflectance};
  return m;
}

}  // namespace clpt::test
