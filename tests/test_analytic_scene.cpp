// Scenes whose image is known exactly.
#include <gtest/gtest.h>

#include <cmath>

#include "device_test_util.h"
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
