// Area lights (emitting triangles sampled by next-event estimation): analytic images, nee against
// the book estimator on the Cornell box, and the noise nee saves there. PoCL, fixed seeds, small
// images; every threshold is a z of the estimators' own variance (Sidak over the comparisons).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "device_test_util.h"
#include "mesh_test_util.h"
#include "render/megakernel_renderer.h"
#include "render/render_plan.h"
#include "render_test_util.h"
#include "scene/device_scene.h"
#include "scene/light_pick.h"

namespace clpt::test {
namespace {

// A camera at (0, 0, 5) inside a closed emitting box of 12 triangles (radiance Le, normals
// outwards: every point the ball sees is a back face, so this checks two-sided emission in both
// strategies) around a Lambertian ball of albedo a at the origin. Every point of the ball sees
// emission Le in every direction, so its pixels are exactly a Le in expectation.
Scene emitting_box_furnace(double le, bool tessellated_ball, double albedo) {
  Scene scene;
  scene.file = "analytic";
  scene.camera.position = {0, 0, 5};
  scene.camera.look_at = {0, 0, 0};
  scene.meshes.push_back(closed_box({-6, -6, -6}, {6, 6, 8}, emitter(le)));
  if (tessellated_ball) {
    scene.meshes.push_back(tessellated_sphere({0, 0, 0}, 1, 24, 32, lambertian(albedo)));
  } else {
    Sphere ball;
    ball.name = "ball";
    ball.radius = 1;
    ball.material = lambertian(albedo);
    scene.spheres = {ball};
  }
  return scene;
}

// The book estimator gives every pixel wholly on the ball exactly a Le and every other pixel Le
// (zero variance: one bounce, then the box); nee's estimate of those ball pixels, pooled, must be
// a Le within its variance, and its emitter pixels exactly Le (camera rays have MIS weight 1).
// nee's ball pixels have variance (light samples and BSDF hits share the estimate), which
// shows that the shadow rays found the triangles.
TEST(AreaLights, EmittingBoxFurnaceGivesAlbedoTimesLe) {
  const double le = 1.5, albedo = 0.6;
  const int w = 40, h = 30;
  for (bool tessellated : {false, true}) {
    SCOPED_TRACE(tessellated ? "tessellated ball" : "sphere ball");
    Scene scene = emitting_box_furnace(le, tessellated, albedo);
    // The same seed and samples: the camera rays are the same, so a pixel the book sees wholly
    // on the ball is wholly on the ball for nee too.
    scene.settings.estimator = "book";
    const TestRender book = render_for_test(scene, w, h, 64, 4);
    scene.settings.estimator = "nee";
    const TestRender nee = render_for_test(scene, w, h, 64, 4);
    const auto book_mean = book.film.mean_rgb(), book_var = book.film.variance_rgb();
    const auto mean = nee.film.mean_rgb(), var = nee.film.variance_rgb();
    double sum = 0, sum_var = 0;
    int ball = 0, box = 0;
    for (size_t i = 0; i < mean.size(); ++i) {
      if (book_var[i] > 1e-7 * le * le) continue;  // a silhouette pixel
      if (std::abs(book_mean[i] - le) <= 1e-6 * le) {
        ++box;
        EXPECT_NEAR(mean[i], le, 1e-6 * le) << "value " << i;
      } else if (std::abs(book_mean[i] - albedo * le) <= 1e-6 * le) {
        if (i % 3 != 0) continue;  // grey: the channels are the same estimate, pooled once
        ++ball;
        sum += mean[i];
        sum_var += var[i];
      } else {
        ADD_FAILURE() << "book pixel value " << i << " is " << book_mean[i];
      }
    }
    ASSERT_GT(ball, 150);
    EXPECT_GT(box, 3 * 800);
    const double pooled = sum / ball, pooled_sigma = std::sqrt(sum_var) / ball;
    std::printf("emitting box furnace (%s): nee ball mean %.6f, expected %.6f, sigma %.2e, z %+.2f\n",
                tessellated ? "tessellated" : "sphere", pooled, albedo * le, pooled_sigma,
                (pooled - albedo * le) / pooled_sigma);
    EXPECT_GT(sum_var, 0.0);
    EXPECT_LE(std::abs(pooled - albedo * le), sidak_z(2) * pooled_sigma);
    EXPECT_EQ(nee.report.dropped, 0u);
  }
}

// Irradiance at the point under the centre of a square emitter of radiance Le and side 2s,
// parallel at height h: four rectangles with a corner above the point, each of form factor
// (1 / 2 pi) 2 A / sqrt(1 + A^2) atan(A / sqrt(1 + A^2)), A = s / h, so
// E = pi Le 4 F = 4 Le A / sqrt(1 + A^2) atan(A / sqrt(1 + A^2)) (1.7408 Le for s = h; a midpoint
// sum of Le h^2 / r^4 over the square gives the same to 1e-7).
double square_irradiance(double le, double s, double h) {
  const double a = s / h, q = a / std::sqrt(1 + a * a);
  return 4 * le * q * std::atan(q);
}

// A square light (two triangles, facing down) above a Lambertian floor of albedo rho, nothing
// else, one bounce (max_bounces 1, black background): the floor point under the light's centre
// has radiance rho E / pi exactly. The camera looks at that point from the side, under the light
// (which it does not see), with a 2-degree field of view: the centre 3x3 of 9x9 pixels see the
// floor within 0.02 units of the point, where E differs from its centre value by under 1e-3
// relative (it is flat to second order there), the allowance besides the estimator's sigma.
TEST(AreaLights, FloorUnderSquareLightMatchesClosedForm) {
  const double le = 4, s = 1, h = 1, rho = 0.5;
  Scene scene;
  scene.file = "analytic";
  scene.camera.position = {0, 0.9, -1.1};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.vertical_fov_deg = 2;
  TriangleMesh light;
  light.name = "light";
  light.positions = {{-s, h, -s}, {s, h, -s}, {s, h, s}, {-s, h, s}};
  light.triangles = {{0, 1, 2}, {0, 2, 3}};
  light.material = emitter(le);
  TriangleMesh floor;
  floor.name = "floor";
  const double f = 1000;
  floor.positions = {{-f, 0, -f}, {f, 0, -f}, {f, 0, f}, {-f, 0, f}};
  floor.triangles = {{0, 2, 1}, {0, 3, 2}};
  floor.material = lambertian(rho);
  scene.meshes = {light, floor};
  scene.settings.max_bounces = 1;
  const double expected = rho * square_irradiance(le, s, h) / 3.14159265358979323846;
  for (const char* estimator : {"nee", "book"}) {
    scene.settings.estimator = estimator;
    const int w = 9, hgt = 9;
    const TestRender r = render_for_test(scene, w, hgt, 1024, 11);
    const RegionStats centre = region_stats(r.film.mean_rgb(), r.film.variance_rgb(), w, 3, 3, 6, 6);
    for (int c = 0; c < 3; ++c) {
      const double sigma = std::sqrt(centre.variance_of_mean[c]);
      std::printf("floor under a square light, %s, channel %d: %.6f, closed form %.6f, sigma %.2e\n", estimator, c,
                  centre.mean[c], expected, sigma);
      EXPECT_LE(std::abs(centre.mean[c] - expected), sidak_z(6) * sigma + 1e-3 * expected) << estimator;
    }
  }
}

// The Cornell box, lit only by its ceiling quad: nee (light samples of its two triangles and
// BSDF hits, MIS) and the book estimator (BSDF hits only) estimate the same image. 32x32; the
// book's 1024 samples leave its pixels heavy-tailed (most samples of a dim pixel never reach the
// small light, so the sample variance underestimates), hence 8x8-pixel blocks, 16 of them and 3
// channels, each block mean tested against the two variances (Sidak, family-wise 1%).
// Then the noise: nee's per-sample variance summed over the image, against the book's (printed;
// asserted only to be lower, where 2.3x lower was measured).
TEST(AreaLights, CornellBoxNeeMatchesBookAndIsLessNoisy) {
  Scene scene = load_book_scene("cornell-box");
  const int w = 32, h = 32, block = 8;
  const int64_t book_spp = 1024, nee_spp = 256;
  scene.settings.estimator = "book";
  const TestRender book = render_for_test(scene, w, h, book_spp, 21);
  scene.settings.estimator = "nee";
  const TestRender nee = render_for_test(scene, w, h, nee_spp, 22);
  const auto bm = book.film.mean_rgb(), bv = book.film.variance_rgb();
  const auto nm = nee.film.mean_rgb(), nv = nee.film.variance_rgb();
  const int blocks = (w / block) * (h / block);
  const double z = sidak_z(3 * blocks);
  double worst = 0;
  for (int by = 0; by < h; by += block)
    for (int bx = 0; bx < w; bx += block) {
      const RegionStats a = region_stats(bm, bv, w, bx, by, bx + block, by + block);
      const RegionStats b = region_stats(nm, nv, w, bx, by, bx + block, by + block);
      for (int c = 0; c < 3; ++c) {
        const double zc = (a.mean[c] - b.mean[c]) / std::sqrt(a.variance_of_mean[c] + b.variance_of_mean[c]);
        worst = std::max(worst, std::abs(zc));
        EXPECT_LE(std::abs(zc), z) << "block (" << bx << ", " << by << ") channel " << c << ": book "
                                   << a.mean[c] << ", nee " << b.mean[c];
      }
    }
  // Per-sample variance = variance of the mean x samples; summed over pixels and channels.
  double book_sample_var = 0, nee_sample_var = 0;
  for (size_t i = 0; i < bv.size(); ++i) {
    book_sample_var += double(bv[i]) * double(book_spp);
    nee_sample_var += double(nv[i]) * double(nee_spp);
  }
  std::printf("Cornell box %dx%d: worst block |z| %.2f (bound %.2f); per-sample variance summed over the image: "
              "book %.4g, nee %.4g (%.2fx lower at equal spp)\n",
              w, h, worst, z, book_sample_var, nee_sample_var, book_sample_var / nee_sample_var);
  EXPECT_LT(nee_sample_var, book_sample_var);
}

// The pick distribution: the Cornell box with a second, dim and large light (a 400 x 400 panel of
// radiance 0.05 on the back wall, two triangles), rendered with the power pick clpt uses and with
// the same light list picked uniformly (the table refilled by hand, each triangle's density
// with it). Any pick is unbiased when both MIS strategies use its density, so the two images
// must agree (block means, as above); the per-sample variances are printed (measured: power
// 463.6 against uniform 475.8, 2.6% lower, at the same cost per sample).
TEST(AreaLights, PowerAndUniformPicksGiveTheSameImage) {
  Scene scene = load_book_scene("cornell-box");
  TriangleMesh panel;
  panel.name = "panel";
  panel.positions = {{478, 74, 558}, {78, 74, 558}, {78, 474, 558}, {478, 474, 558}};
  panel.triangles = {{0, 1, 2}, {0, 2, 3}};
  panel.material = emitter(0.05);
  scene.meshes.push_back(panel);
  const int w = 32, h = 32, spp = 256, block = 8;
  scene.settings.width = w;
  scene.settings.height = h;
  scene.settings.seed = 5;
  std::vector<float> mean[2], var[2];
  double sample_var[2] = {0, 0};
  for (int uniform = 0; uniform < 2; ++uniform) {
    DeviceScene ds = make_device_scene(scene, w, h);
    ASSERT_EQ(ds.lights.size(), 4u);
    if (uniform) {
      fill_light_pick(ds.lights, std::vector<double>(ds.lights.size(), 1.0));
      for (const GpuLight& l : ds.lights)
        ds.triangle_shading[l.triangle].light_area_density = l.pick_probability / l.cap_area;
    } else {
      EXPECT_GT(ds.lights[0].pick_probability, 0.4f);  // the ceiling light's 2 x 47.5%
    }
    MegakernelRenderer renderer(test_device(), ds, features_for_scene(scene));
    GpuRenderParams p = make_params(scene, ds);
    p.seed_lo = uint32_t(5 + uniform);
    p.samples_per_pass = 32;
    Film film(w, h);
    for (int s = 0; s < spp; s += 32) {
      p.sample_begin = uint32_t(s);
      film.add_pass(renderer.render_pass(p), 0, 32);
    }
    mean[uniform] = film.mean_rgb();
    var[uniform] = film.variance_rgb();
    for (float v : var[uniform]) sample_var[uniform] += double(v) * spp;
  }
  const double z = sidak_z(3 * (w / block) * (h / block));
  for (int by = 0; by < h; by += block)
    for (int bx = 0; bx < w; bx += block) {
      const RegionStats a = region_stats(mean[0], var[0], w, bx, by, bx + block, by + block);
      const RegionStats b = region_stats(mean[1], var[1], w, bx, by, bx + block, by + block);
      for (int c = 0; c < 3; ++c)
        EXPECT_LE(std::abs(a.mean[c] - b.mean[c]), z * std::sqrt(a.variance_of_mean[c] + b.variance_of_mean[c]))
            << "block (" << bx << ", " << by << ") channel " << c;
    }
  std::printf("Cornell box with a dim panel, %dx%d, %d spp: per-sample variance summed over the image: power pick "
              "%.4g, uniform pick %.4g\n",
              w, h, spp, sample_var[0], sample_var[1]);
}

}  // namespace
}  // namespace clpt::test
