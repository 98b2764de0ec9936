// Triangle meshes built in code for tests (until scene files carry meshes, and for geometry the
// tests need exactly): a tessellated sphere, a closed box and a random triangle soup, each as the
// loader leaves a mesh in Scene::meshes (scene/scene.h, TriangleMesh).
#pragma once

#include <random>

#include "scene/scene.h"

namespace clpt::test {

// A UV sphere of `rings` latitude bands and `segments` longitude segments (rings >= 2,
// segments >= 3): closed, vertices shared between neighbouring triangles, wound so that the
// geometric normal points outwards. With `normals`, the exact sphere normal at every vertex.
TriangleMesh tessellated_sphere(const Vec3& center, double radius, int rings, int segments,
                                const Material& material, bool normals = false);

// The closed box [lower, upper], 8 shared vertices and 12 triangles, normals outwards.
TriangleMesh closed_box(const Vec3& lower, const Vec3& upper, const Material& material);

// `count` random triangles with vertices uniform in the cube of half-width `extent` around
// `center`, each triangle at most `size` across.
TriangleMesh random_soup(std::mt19937& rng, int count, const Vec3& center, double extent, double size,
                         const Material& material);

// The Cornell box (as loaded from scenes/cornell-box.toml) with its two blocks replaced by a
// tessellated ball of 768 small triangles: its walls, floor and ceiling (10 triangles, five meshes,
// each triangle over 100 times the median's area) go to the triangle loop beside a hierarchy of the
// ball's and the light's (scene/loop_spheres.h, loop_meshes).
Scene cornell_box_with_ball(Scene cornell_box);

Material lambertian(double albedo);
Material emitter(double radiance);
Material mirror(double reflectance);

}  // namespace clpt::test
