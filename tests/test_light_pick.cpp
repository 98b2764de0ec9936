// The light list and its pick (scene/light_pick.h, scene/device_scene.h) and the decision to
// compile triangle lights (kernels/kernel_options.cpp): exact, host only.
#include <gtest/gtest.h>

#include <random>

#include "kernels/kernel_options.h"
#include "mesh_test_util.h"
#include "render_test_util.h"
#include "scene/device_scene.h"
#include "scene/light_pick.h"
#include "util/error.h"

namespace clpt::test {
namespace {

// The table's draw reproduces every weight: uniform, skewed, with zeros, random.
TEST(LightPick, AliasTableDrawsEachEntryWithItsProbability) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::vector<std::vector<double>> cases = {{1}, {1, 1, 1}, {1, 0, 3}, {1e-6, 1, 1e6}, {0, 0, 2, 0}};
  std::vector<double> random(257);
  for (double& w : random) w = uniform(rng) * uniform(rng);
  cases.push_back(random);
  for (const auto& weights : cases) {
    std::vector<GpuLight> lights(weights.size());
    fill_light_pick(lights, weights);
    double total = 0;
    for (double w : weights) total += w;
    const std::vector<double> drawn = alias_table_probabilities(lights);
    for (size_t i = 0; i < weights.size(); ++i) {
      EXPECT_NEAR(lights[i].pick_probability, weights[i] / total, 1e-7 * (1 + weights[i] / total)) << i;
      EXPECT_NEAR(drawn[i], weights[i] / total, 1e-6 / double(weights.size()) + 1e-6 * weights[i] / total) << i;
      EXPECT_LT(lights[i].alias, weights.size());
      EXPECT_GE(lights[i].alias_threshold, 0.0f);
      EXPECT_LE(lights[i].alias_threshold, 1.0f);
    }
  }
}

TEST(LightPick, RejectsWeightsThatAreNoDistribution) {
  std::vector<GpuLight> lights(2);
  EXPECT_THROW(fill_light_pick(lights, {0, 0}), Error);
  EXPECT_THROW(fill_light_pick(lights, {1, -1}), Error);
  EXPECT_THROW(fill_light_pick(lights, {1}), Error);
}

// The Cornell box's light quad becomes two triangle lights picked by area (same emission), each
// triangle's shading record holding pick probability / area; no other triangle is a light.
TEST(LightPick, CornellBoxLightIsTwoTrianglesPickedByArea) {
  const Scene scene = load_book_scene("cornell-box");
  const DeviceScene ds = make_device_scene(scene, 32, 32);
  ASSERT_EQ(ds.lights.size(), 2u);
  double area = 0;
  for (const GpuLight& l : ds.lights) {
    ASSERT_NE(l.triangle, CLPT_LIGHT_SPHERE);
    EXPECT_EQ(ds.triangle_shading[l.triangle].material.kind, CLPT_MATERIAL_EMITTER);
    EXPECT_FLOAT_EQ(l.pick_probability, 0.5f);  // two halves of one rectangle
    EXPECT_FLOAT_EQ(ds.triangle_shading[l.triangle].light_area_density, l.pick_probability / l.cap_area);
    area += l.cap_area;
  }
  EXPECT_NEAR(area, 130.0 * 105.0, 1e-3);  // the page's 130 mm x 105 mm light
  int densities = 0;
  for (const GpuTriangleShading& s : ds.triangle_shading) densities += s.light_area_density > 0;
  EXPECT_EQ(densities, 2);
}

// Sphere lights first, then the triangles; by power (area x mean radiance) once a triangle is a
// light: the book's light (cap area 6.29, radiance 12) beside an emitting quad of area 2 and
// radiance 3. Without triangle lights the pick stays uniform (what those kernels draw).
TEST(LightPick, SpheresAndTrianglesInOneListByPower) {
  Scene scene = load_book_scene("diffuse");
  const DeviceScene spheres_only = make_device_scene(scene, 32, 24);
  ASSERT_EQ(spheres_only.lights.size(), 1u);
  EXPECT_EQ(spheres_only.lights[0].triangle, CLPT_LIGHT_SPHERE);
  EXPECT_FLOAT_EQ(spheres_only.lights[0].pick_probability, 1.0f);

  TriangleMesh quad;
  quad.name = "panel";
  quad.positions = {{-1, 1, 0}, {1, 1, 0}, {1, 1, 1}, {-1, 1, 1}};
  quad.triangles = {{0, 1, 2}, {0, 2, 3}};
  quad.material = emitter(3);
  scene.meshes.push_back(quad);
  const DeviceScene ds = make_device_scene(scene, 32, 24);
  ASSERT_EQ(ds.lights.size(), 3u);
  EXPECT_EQ(ds.lights[0].triangle, CLPT_LIGHT_SPHERE);
  const Material& sphere_light = scene.spheres[ds.lights[0].sphere].material;
  const double sphere_power = ds.lights[0].cap_area * sphere_light.emission[0];
  const double triangle_power = 1.0 * 3.0;  // each triangle: area 1, radiance 3
  const double total = sphere_power + 2 * triangle_power;
  EXPECT_NEAR(ds.lights[0].pick_probability, sphere_power / total, 1e-6);
  for (int i = 1; i < 3; ++i) {
    EXPECT_NE(ds.lights[size_t(i)].triangle, CLPT_LIGHT_SPHERE);
    EXPECT_NEAR(ds.lights[size_t(i)].pick_probability, triangle_power / total, 1e-6);
    EXPECT_NEAR(ds.lights[size_t(i)].cap_area, 1.0, 1e-6);
  }
}

// Triangle lights are compiled only for nee on a scene with an emitting mesh (or the generic
// kernel): the book's scenes, a mesh scene whose meshes do not emit, and the book estimator keep
// -DCLPT_HAS_TRIANGLE_LIGHTS=0, i.e. the kernel they had before (light.cl's uniform pick over
// the spheres' caps; no triangle sampling, no alias draw, no skipped triangle in bvh.cl).
TEST(LightPick, TriangleLightsCompiledOnlyWhereTheSceneHasThem) {
  const auto option = [](const Scene& s) {
    const std::string o = kernel_build_options(features_for_scene(s));
    return o.find("-DCLPT_HAS_TRIANGLE_LIGHTS=1") != std::string::npos   ? 1
           : o.find("-DCLPT_HAS_TRIANGLE_LIGHTS=0") != std::string::npos ? 0
                                                                         : -1;
  };
  Scene cornell = load_book_scene("cornell-box");
  ASSERT_EQ(cornell.settings.estimator, "nee");
  EXPECT_EQ(option(cornell), 1);
  EXPECT_NE(explain_kernel_options(features_for_scene(cornell)).find("triangle lights: compiled"), std::string::npos);
  cornell.settings.estimator = "book";
  EXPECT_EQ(option(cornell), 0);
  for (const char* name : {"diffuse", "specular", "glass"}) {
    Scene scene = load_book_scene(name);
    scene.settings.estimator = "nee";
    EXPECT_EQ(option(scene), 0) << name;
    scene.meshes.push_back(closed_box({0, 0, 0}, {1, 1, 1}, lambertian(0.5)));
    EXPECT_EQ(option(scene), 0) << name << " with a Lambertian mesh";
    EXPECT_NE(explain_kernel_options(features_for_scene(scene)).find("triangle lights: left out (no emitting mesh"),
              std::string::npos);
  }
  EXPECT_NE(kernel_build_options(generic_features()).find("-DCLPT_HAS_TRIANGLE_LIGHTS=1"), std::string::npos);
}

}  // namespace
}  // namespace clpt::test
