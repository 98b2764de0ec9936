// Scenes whose image is known exactly.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "device_test_util.h"
#include "mesh_test_util.h"
#include "kernels/kernel_options.h"
#include "render/megakernel_renderer.h"
#include "render_test_util.h"
#include "scene/device_scene.h"

namespace clpt::test {
namespace {

// A camera inside an emitting sphere of radiance Le that holds a Lambertian ball of albedo a:
// with the book's estimator a camera ray sees Le on the emitter, and a * Le on the ball (one
// bounce, which can only reach the emitter). Every sample of a pixel wholly on one of them has the
// same value: zero variance, exact.
Scene furnace_scene(double le, double albedo) {
  Scene scene;
  scene.file = "analytic";
  scene.camera.position = {0, 0, 5};
  scene.camera.look_at = {0, 0, 0};
  Sphere emitter;
  emitter.name = "enclosure";
  emitter.radius = 20;
  emitter.material.type = MaterialType::Emitter;
  emitter.material.emission = {le, le, le};
  Sphere ball;
  ball.name = "ball";
  ball.radius = 1;
  ball.material.type = MaterialType::Lambertian;
  ball.material.reflectance = {albedo, albedo, albedo};
  scene.spheres = {emitter, ball};
  return scene;
}

TEST(AnalyticScene, CameraInsideEmitterSeesLeAndAlbedoTimesLe) {
  const double le = 2.5, albedo = 0.6;
  const TestRender r = render_for_test(furnace_scene(le, albedo), 48, 36, 64, 3);
  const auto mean = r.film.mean_rgb();
  const auto var = r.film.variance_rgb();
  int on_emitter = 0, on_ball = 0;
  for (size_t i = 0; i < mean.size(); ++i) {
    EXPECT_GE(mean[i], albedo * le * (1 - 1e-6));
    EXPECT_LE(mean[i], le * (1 + 1e-6));
    if (var[i] > 1e-9 * le * le) continue;  // a pixel on the ball's silhouette (float sums leave ~1e-14)
    if (std::abs(mean[i] - le) <= 1e-6 * le) ++on_emitter;
    else if (std::abs(mean[i] - albedo * le) <= 1e-6 * le) ++on_ball;
    else ADD_FAILURE() << "zero-variance pixel " << i / 3 << " has " << mean[i];
  }
  // The ball (radius 1 at distance 5, 36.87 degree field of view) covers about 13% of the image.
  EXPECT_GT(on_ball, 3 * 150);
  EXPECT_GT(on_emitter, 3 * 1000);
  EXPECT_EQ(r.report.dropped, 0u);
}

// Every pixel of a furnace render is one of `levels` (zero variance, within 1e-6 relative) or a
// silhouette pixel between them; counts the pixels (channels) at each level.
std::vector<int> count_levels(const TestRender& r, const std::vector<double>& levels, double le) {
  const auto mean = r.film.mean_rgb();
  const auto var = r.film.variance_rgb();
  std::vector<int> counts(levels.size(), 0);
  for (size_t i = 0; i < mean.size(); ++i) {
    EXPECT_LE(mean[i], le * (1 + 1e-6)) << "value " << i;
    // A silhouette pixel. (The film's variance of a constant sample comes out near 1e-8 Le^2 from
    // float cancellation in sum_sq / n - mean^2; one black sample in 16 would give 0.06 value^2.)
    if (var[i] > 1e-7 * le * le) continue;
    bool found = false;
    for (size_t k = 0; k < levels.size() && !found; ++k)
      if (std::abs(mean[i] - levels[k]) <= 1e-6 * le) {
        ++counts[k];
        found = true;
      }
    if (!found) ADD_FAILURE() << "zero-variance pixel " << i / 3 << " has " << mean[i];
  }
  return counts;
}

// A mirror ball of reflectance rho in the furnace: a camera ray reflects once off the convex ball
// and can only reach the emitter, so the ball's pixels are exactly rho Le, with either estimator.
TEST(AnalyticScene, MirrorBallInFurnaceIsReflectanceTimesLe) {
  const double le = 2.5, rho = 0.7;
  for (const char* estimator : {"book", "nee"}) {
    Scene scene = furnace_scene(le, 0.5);
    scene.spheres[1].material = mirror(rho);
    scene.settings.estimator = estimator;
    const TestRender r = render_for_test(scene, 48, 36, 16, 3);
    const std::vector<int> counts = count_levels(r, {le, rho * le}, le);
    EXPECT_GT(counts[1], 3 * 150) << estimator;
    EXPECT_GT(counts[0], 3 * 1000) << estimator;
  }
}

// The furnace with its ball made of triangles: a convex tessellated sphere, Lambertian or a mirror
// (flat facets reflect into the emitter after one bounce just as the sphere does), without shading
// normals: albedo Le exactly.
TEST(AnalyticScene, TessellatedBallInFurnaceIsAlbedoTimesLe) {
  const double le = 2.5;
  for (const Material& m : {lambertian(0.6), mirror(0.8)}) {
    Scene scene = furnace_scene(le, 0.5);
    scene.spheres.pop_back();
    scene.meshes.push_back(tessellated_sphere({0, 0, 0}, 1, 24, 32, m));
    const TestRender r = render_for_test(scene, 48, 36, 16, 3);
    const std::vector<int> counts = count_levels(r, {le, m.reflectance[0] * le}, le);
    EXPECT_GT(counts[1], 3 * 150) << material_type_name(m.type);
    EXPECT_GT(counts[0], 3 * 1000) << material_type_name(m.type);
    EXPECT_EQ(r.report.dropped, 0u);
  }
}

// The enclosure itself made of triangles: a closed emitting box (12 triangles) around the camera
// and a Lambertian sphere. A ray that slipped between the box's triangles would leave a black
// sample (variance, and a mean below Le): every pixel off the ball must be exactly Le.
TEST(AnalyticScene, ClosedEmittingBoxOfTrianglesLeaksNothing) {
  const double le = 1.5, albedo = 0.4;
  Scene scene = furnace_scene(le, albedo);
  scene.spheres.erase(scene.spheres.begin());
  scene.meshes.push_back(closed_box({-6, -6, -6}, {6, 6, 8}, emitter(le)));
  const TestRender r = render_for_test(scene, 48, 36, 16, 3);
  const std::vector<int> counts = count_levels(r, {le, albedo * le}, le);
  EXPECT_GT(counts[1], 3 * 150);
  EXPECT_GT(counts[0], 3 * 1000);
}

// Grazing rays at a mesh with shading normals: a light inside a closed, coarsely tessellated
// Lambertian sphere whose interpolated normals tilt far from its facets, seen from outside
// against a black background. No light may come through the surface: the image is black, with
// either estimator (BSDF rays bent below a facet by its shading normal carry nothing, and shadow
// rays hit the facet).
TEST(AnalyticScene, ShadingNormalMeshLetsNoLightThrough) {
  for (const char* estimator : {"book", "nee"}) {
    Scene scene;
    scene.file = "analytic";
    scene.camera.position = {0, 0, 5};
    scene.camera.look_at = {0, 0, 0};
    Sphere light;
    light.name = "light";
    light.radius = 0.3;
    light.material = emitter(10);
    scene.spheres = {light};
    scene.meshes.push_back(tessellated_sphere({0, 0, 0}, 1, 5, 6, lambertian(0.9), true));
    scene.settings.estimator = estimator;
    const TestRender r = render_for_test(scene, 40, 30, 32, 5);
    const auto mean = r.film.mean_rgb();
    double worst = 0;
    for (float v : mean) worst = std::max(worst, double(v));
    EXPECT_EQ(worst, 0.0) << estimator;
  }
}

// The image does not depend on how samples are split into passes: the same samples, addressed by
// (seed, pixel, sample index), summed in one pass of 32 or four of 8, agree to float rounding.
TEST(PassSplit, OnePassEqualsFourPasses) {
  const Scene scene = load_book_scene("glass");
  const int w = 40, h = 30;
  const DeviceScene ds = make_device_scene(scene, w, h);
  MegakernelRenderer renderer(test_device(), ds, features_for_scene(scene));
  GpuRenderParams p{};
  p.camera = ds.camera;
  p.width = w;
  p.height = h;
  p.sphere_count = cl_uint(ds.spheres.size());
  p.max_bounces = 9;
  p.seed_lo = 42;
  p.ray_epsilon = ds.ray_epsilon;
  p.pixel_count = w * h;
  Film one(w, h), four(w, h);
  p.samples_per_pass = 32;
  one.add_pass(renderer.render_pass(p), 0, 32);
  p.samples_per_pass = 8;
  for (cl_uint s = 0; s < 32; s += 8) {
    p.sample_begin = s;
    four.add_pass(renderer.render_pass(p), 0, 8);
  }
  const auto a = one.mean_rgb(), b = four.mean_rgb();
  for (size_t i = 0; i < a.size(); ++i) ASSERT_NEAR(a[i], b[i], 1e-5f * (1 + a[i])) << "value " << i;
}

}  // namespace
}  // namespace clpt::test
