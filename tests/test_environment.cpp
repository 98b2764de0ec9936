// The environment light (docs/environment.md): the mapping as issue 34 states it, the sampling
// distribution (its density integrates to 1, the device's alias draws match the host's CDFs,
// chi-square of the device's samples), camera rays in known directions seeing a marker image's
// texels, furnaces (a white Lambertian ball under a constant environment renders the
// environment's radiance everywhere), a floor under a sky whose sun is 1e5 times the sky against
// the closed form of its irradiance, and MIS against BSDF sampling alone. Fixed seeds; thresholds
// from each estimate's own variance (Sidak over the comparisons) plus float rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>

#include "device_test_util.h"
#include "io/exr_writer.h"
#include "io/image_io.h"
#include "mesh_test_util.h"
#include "render_test_util.h"
#include "scene/environment.h"
#include "scene/environment_map.h"
#include "stat_test_util.h"
#include "util/temporary_directory.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A sky of w x h texels: blue, brighter towards the horizon, a dark ground, and a "sun" of the
// texels within `sun_degrees` of (0.3, 0.6, -0.74) at `sun_ratio` times the zenith.
Environment sky(int w, int h, double sun_ratio, double sun_degrees = 6) {
  Environment e;
  e.file = "test_sky";
  e.what = "test";
  e.width = w;
  e.height = h;
  auto rgb = std::make_shared<std::vector<float>>(size_t(w) * h * 3);
  const Vec3 sun_dir = [] {
    const Vec3 d{0.3, 0.6, -0.74};
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    return Vec3{d[0] / n, d[1] / n, d[2] / n};
  }();
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      const Vec3 d = environment_direction((col + 0.5) / w, (row + 0.5) / h);
      float* p = &(*rgb)[3 * (size_t(row) * w + col)];
      const double t = d[1] > 0 ? 1 - d[1] : 0;
      const float sky_r = float(0.1 + 0.3 * t), sky_g = float(0.2 + 0.3 * t), sky_b = float(0.5 + 0.2 * t);
      const bool ground = d[1] < 0;
      p[0] = ground ? 0.1f : sky_r, p[1] = ground ? 0.1f : sky_g, p[2] = ground ? 0.08f : sky_b;
      const double c = d[0] * sun_dir[0] + d[1] * sun_dir[1] + d[2] * sun_dir[2];
      if (c > std::cos(sun_degrees * kPi / 180))
        for (int k = 0; k < 3; ++k) p[k] = float(0.5 * sun_ratio);
    }
  e.rgb = rgb;
  e.hash = "test";
  return e;
}

RenderReport last_report;
Film render(Scene scene, int w, int h, int64_t spp, uint64_t seed, std::optional<ExecutionForm> form = {},
            Precision precision = Precision::Robust, bool generic = false) {
  RenderRequest request = test_request(std::move(scene), w, h, spp, seed);
  request.precision = precision;
  request.form = form;
  request.generic_kernel = generic;
  return run_render(request, last_report);
}

// ---- the mapping, on the host, against the issue's words ------------------------------------

TEST(EnvironmentMapping, IssueConventions) {
  const auto uv = [](Vec3 d) { return environment_uv(d); };
  EXPECT_NEAR(uv({1, 0, 0})[0], 0.5, 1e-12);   // the image's horizontal centre looks along +X
  EXPECT_NEAR(uv({0, 0, -1})[0], 0.25, 1e-12);  // u = 0.25 along -Z
  EXPECT_NEAR(uv({0, 0, 1})[0], 0.75, 1e-12);   // u = 0.75 along +Z
  EXPECT_NEAR(uv({0, 1, 0})[1], 0.0, 1e-12);    // the top row is the zenith
  EXPECT_NEAR(uv({1, 0, 0})[1], 0.5, 1e-12);
  EXPECT_NEAR(uv({0, -1, 0})[1], 1.0, 1e-12);
  for (double u : {0.1, 0.37, 0.5, 0.81})
    for (double v : {0.05, 0.5, 0.93}) {
      const auto back = environment_uv(environment_direction(u, v));
      EXPECT_NEAR(back[0], u, 1e-12);
      EXPECT_NEAR(back[1], v, 1e-12);
    }
  // rotation_deg turns the environment about +Y, right-handed: +90 brings +X to -Z.
  const Vec3 turned = environment_to_world({1, 0, 0}, 90);
  EXPECT_NEAR(turned[0], 0, 1e-12);
  EXPECT_NEAR(turned[2], -1, 1e-12);
  const Vec3 back = environment_to_local(turned, 90);
  EXPECT_NEAR(back[0], 1, 1e-12);
}

// ---- the distribution ------------------------------------------------------------------------

TEST(EnvironmentDistribution, PdfIntegratesToOne) {
  for (const double ratio : {1.0, 1e5}) {
    const Environment e = sky(32, 16, ratio);
    const EnvironmentDistribution d = environment_distribution(e.width, e.height, *e.rgb);
    // Midpoint rule in (theta, phi) on a grid 20 times finer than the texels (aligned with them):
    // pdf sin(theta) is constant over each texel, so the sum is exact up to rounding.
    const int nt = 16 * 20, np = 32 * 20;
    double integral = 0;
    for (int i = 0; i < nt; ++i) {
      const double theta = kPi * (i + 0.5) / nt;
      for (int j = 0; j < np; ++j) {
        const Vec3 dir = environment_direction((j + 0.5) / np, (i + 0.5) / nt);
        integral += d.pdf(dir) * std::sin(theta) * (kPi / nt) * (2 * kPi / np);
      }
    }
    EXPECT_NEAR(integral, 1.0, 1e-9) << "sun ratio " << ratio;
    double total = 0;
    for (size_t t = 0; t < d.f.size(); ++t) total += d.texel_probability(t);
    EXPECT_NEAR(total, 1.0, 1e-12);
    // The texel probabilities are f / sum f, and the density their (u, v) form.
    double sum_f = 0;
    for (double f : d.f) sum_f += f;
    for (size_t t = 0; t < d.f.size(); ++t) {
      EXPECT_NEAR(d.texel_probability(t), d.f[t] / sum_f, 1e-12);
      EXPECT_NEAR(d.density_uv(t), d.texel_probability(t) * double(d.f.size()), 1e-9 * d.density_uv(t) + 1e-12);
    }
  }
}

// The device's words: the alias tables draw each row and texel with the CDFs' probabilities.
TEST(EnvironmentDistribution, AliasTablesDrawTheCdfsProbabilities) {
  const Environment e = sky(24, 12, 1e5);
  const std::vector<float> words = environment_device_data(e, false);
  const GpuEnvironment header = environment_header(words);
  ASSERT_EQ(header.kind, CLPT_ENVIRONMENT_IMAGE);
  EXPECT_EQ(header.pick_probability, 1.0f);
  const EnvironmentDistribution d = environment_distribution(e.width, e.height, *e.rgb);
  const auto alias_probabilities = [&](uint32_t offset, size_t n) {
    std::vector<double> p(n, 0.0);
    for (size_t i = 0; i < n; ++i) {
      const float threshold = words[offset + 2 * i];
      uint32_t alias;
      std::memcpy(&alias, &words[offset + 2 * i + 1], sizeof alias);
      EXPECT_LT(alias, n);
      p[i] += threshold / double(n);
      p[alias] += (1 - double(threshold)) / double(n);
    }
    return p;
  };
  const std::vector<double> rows = alias_probabilities(header.row_alias_offset, size_t(e.height));
  for (int r = 0; r < e.height; ++r) {
    EXPECT_NEAR(rows[r], d.marginal_cdf[r + 1] - d.marginal_cdf[r], 1e-6) << "row " << r;
    const std::vector<double> cols =
        alias_probabilities(header.column_alias_offset + uint32_t(2 * r * e.width), size_t(e.width));
    for (int c = 0; c < e.width; ++c) {
      const double* cdf = &d.conditional_cdf[size_t(r) * (e.width + 1)];
      EXPECT_NEAR(cols[c], cdf[c + 1] - cdf[c], 1e-6) << "row " << r << " column " << c;
    }
  }
  // Strength scales the texels; with other lights the environment is picked half the time.
  Environment brighter = e;
  brighter.strength = 2;
  const std::vector<float> words2 = environment_device_data(brighter, true);
  EXPECT_EQ(environment_header(words2).pick_probability, 0.5f);
  EXPECT_EQ(words2[environment_header(words2).texel_offset + 5], 2 * (*e.rgb)[5]);
}

// 1e6 device samples of a 16 x 8 sky with a sun at 1e5 x the sky, binned by texel and 2 x 2
// quarters of it in (u, v) (uniform within a texel), against the host CDFs' probabilities; cells
// expecting fewer than 5 pooled; alpha 0.01. And the density each sample returns is
// environment_pdf of its direction, and the host's.
TEST(EnvironmentSampling, DeviceSamplesMatchTheDistribution) {
  const int w = 16, h = 8;
  const Environment e = sky(w, h, 1e5, 12);
  const std::vector<float> words = environment_device_data(e, false);
  const EnvironmentDistribution d = environment_distribution(w, h, *e.rgb);
  constexpr int kSamples = 1000000;
  Buffer env = upload(words);
  Buffer out(test_device(), size_t(kSamples) * 2 * sizeof(cl_float4), CL_MEM_WRITE_ONLY, "samples");
  Kernel kernel(test_program("probe_environment.cl"), "probe_environment_sample", test_device().where());
  kernel.set_arg(0, env);
  kernel.set_arg(1, cl_uint(2026));
  kernel.set_arg(2, out);
  test_device().launch(kernel, kSamples, 0, "probe_environment_sample");
  const std::vector<cl_float4> s = download<cl_float4>(out, size_t(kSamples) * 2);
  std::vector<double> observed(size_t(w) * h * 4, 0.0), expected(observed.size(), 0.0);
  int pdf_mismatches = 0;
  for (int i = 0; i < kSamples; ++i) {
    const Vec3 dir{s[2 * i].s[0], s[2 * i].s[1], s[2 * i].s[2]};
    const auto uv = environment_uv(dir);
    const int cu = std::min(2 * w - 1, int(uv[0] * 2 * w)), cv = std::min(2 * h - 1, int(uv[1] * 2 * h));
    observed[size_t(cv) * 2 * w + cu] += 1;
    const double host_pdf = d.pdf(dir);
    const double pdf = s[2 * i].s[3], again = s[2 * i + 1].s[0];
    if (std::fabs(pdf - host_pdf) > 1e-3 * host_pdf || std::fabs(again - host_pdf) > 1e-3 * host_pdf) ++pdf_mismatches;
  }
  // A sample within float rounding of a texel edge may be looked up in the neighbour.
  EXPECT_LT(pdf_mismatches, kSamples / 10000) << "samples whose density differs from the host's";
  for (int cv = 0; cv < 2 * h; ++cv)
    for (int cu = 0; cu < 2 * w; ++cu)
      expected[size_t(cv) * 2 * w + cu] = d.texel_probability(size_t(cv / 2) * w + cu / 2) / 4 * kSamples;
  const double p = chi2_pooled_p_value(observed, expected);
  EXPECT_GT(p, 0.01) << "chi-square p-value of the samples against the host's CDFs";
}

// ---- orientation: camera rays in known directions see the marker's texels --------------------

// A 5 x 3 marker (odd sizes: u = 0.5 and v = 0.5 are texel centres), texel (c, r) of colour
// (c + 1, r + 1, 10 (c + 1) + r), written as an EXR into a temporary directory and read back
// through the scene layer as --environment reads it.
TEST(EnvironmentOrientation, CameraRaysSeeTheMarkerTexels) {
  install_scene_image_reader();
  TemporaryDirectory dir("clpt-env-marker");
  const std::string path = dir.file("marker.exr");
  const int w = 5, h = 3;
  std::vector<float> pixels;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) pixels.insert(pixels.end(), {float(c + 1), float(r + 1), float(10 * (c + 1) + r)});
  ImageToWrite image;
  image.width = w;
  image.height = h;
  image.channels = {"R", "G", "B"};
  image.pixels = pixels.data();
  ASSERT_EQ(write_exr(path, image), "");
  struct Case {
    Vec3 direction;
    double rotation_deg;
    int column, row;  // the texel the issue's mapping says this direction sees
  };
  const Case cases[] = {
      {{1, 0, 0}, 0, 2, 1},      // +X: the horizontal centre
      {{0, 0, -1}, 0, 1, 1},     // -Z: u = 0.25
      {{0, 0, 1}, 0, 3, 1},      // +Z: u = 0.75
      {{-1, 0, 0.3}, 0, 4, 1},   // -X, a little towards +Z: u = 0.95
      {{0.1, 1, 0.05}, 0, 2, 0}, // near the zenith: the top row
      {{0.2, -1, 0.1}, 0, 2, 2}, // near the nadir: the bottom row
      {{0, 0, -1}, 90, 2, 1},    // turned +90 degrees: -Z sees what +X saw
      {{1, 0, 0}, 90, 3, 1},     // and +X what +Z saw
  };
  for (const Case& k : cases) {
    Scene scene;
    scene.file = "marker";
    const double n = std::sqrt(k.direction[0] * k.direction[0] + k.direction[1] * k.direction[1] +
                               k.direction[2] * k.direction[2]);
    const Vec3 d{k.direction[0] / n, k.direction[1] / n, k.direction[2] / n};
    scene.camera.position = {0, 0, 0};
    scene.camera.look_at = d;
    scene.camera.up = std::fabs(d[1]) > 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    scene.camera.vertical_fov_deg = 1;
    Sphere behind;  // geometry somewhere else: the loader's rule, and a camera ray never hits it
    behind.center = {-100 * d[0], -100 * d[1], -100 * d[2]};
    behind.radius = 1;
    behind.material = lambertian(0.5);
    scene.spheres.push_back(behind);
    scene.settings.estimator = "nee";
    EnvironmentOverrides o;
    o.file = path;
    o.rotation_deg = k.rotation_deg;
    apply_environment_overrides(scene, o);
    for (const ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
      const Film film = render(scene, 1, 1, 4, 5, form);
      const std::vector<float> m = film.mean_rgb();
      EXPECT_FLOAT_EQ(m[0], float(k.column + 1)) << "direction " << d[0] << " " << d[1] << " " << d[2]
                                                 << " rotation " << k.rotation_deg;
      EXPECT_FLOAT_EQ(m[1], float(k.row + 1));
      EXPECT_FLOAT_EQ(m[2], float(10 * (k.column + 1) + k.row));
    }
  }
}

// ---- furnaces --------------------------------------------------------------------------------

// A white Lambertian ball (albedo 1) in the middle of the view, under an environment of uniform
// radiance L: every point of the ball reflects L (it sees the environment whole: convex), and the
// background is L, so every pixel's expectation is L.
Scene furnace_scene(const Environment& e) {
  Scene scene;
  scene.file = "furnace";
  scene.camera.position = {0, 0, 4};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.vertical_fov_deg = 40;
  Sphere ball;
  ball.center = {0, 0, 0};
  ball.radius = 1;
  ball.material = lambertian(1.0);
  scene.spheres.push_back(ball);
  scene.environment = e;
  scene.settings.max_bounces = 3;
  return scene;
}

// A constant environment: no light sample, so each path carries exactly L (cosine sampling of an
// albedo-1 surface has weight 1), in both forms, both estimators, every preset and the generic
// kernel (which samples the constant as a 1 x 1 image under nee: then statistically).
TEST(EnvironmentFurnace, ConstantEnvironmentIsItsRadianceEverywhere) {
  Environment e;
  e.color = {0.5, 0.7, 0.9};
  e.strength = 1.5;
  const float expected[3] = {0.75f, 1.05f, 1.35f};
  for (const char* estimator : {"book", "nee"})
    for (const ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront})
      for (const Precision precision : {Precision::Robust, Precision::Fast}) {
        Scene scene = furnace_scene(e);
        scene.settings.estimator = estimator;
        const Film film = render(scene, 16, 12, 8, 3, form, precision);
        const std::vector<float> m = film.mean_rgb();
        for (size_t i = 0; i < m.size(); ++i)
          ASSERT_NEAR(m[i], expected[i % 3], 2e-5f * expected[i % 3])
              << estimator << " " << execution_form_name(form) << " " << precision_name(precision) << " value " << i;
      }
  Scene scene = furnace_scene(e);
  scene.settings.estimator = "nee";
  const Film film = render(scene, 16, 12, 64, 3, {}, Precision::Robust, true);
  const std::vector<float> m = film.mean_rgb(), v = film.variance_rgb();
  const double z = sidak_z(int(m.size()));
  for (size_t i = 0; i < m.size(); ++i)
    EXPECT_LE(std::fabs(m[i] - expected[i % 3]), z * std::sqrt(v[i]) + 1e-5 * expected[i % 3]) << "generic, value " << i;
}

// An image of uniform radiance, sampled by nee (the image kernel: light samples and BSDF hits
// weighted by MIS): every pixel within z of its own standard error of L, in both forms and with
// the double preset where the device has fp64.
TEST(EnvironmentFurnace, UniformImageUnderMisIsItsRadianceEverywhere) {
  Environment e;
  e.file = "uniform";
  e.width = 8;
  e.height = 4;
  e.rgb = std::make_shared<std::vector<float>>(8 * 4 * 3, 0.8f);
  e.hash = "uniform";
  for (const ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    Scene scene = furnace_scene(e);
    scene.settings.estimator = "nee";
    const Film film = render(scene, 16, 12, 64, 11, form);
    const std::vector<float> m = film.mean_rgb(), v = film.variance_rgb();
    const double z = sidak_z(int(m.size()));
    int off = 0;
    for (size_t i = 0; i < m.size(); ++i) off += std::fabs(m[i] - 0.8) > z * std::sqrt(v[i]) + 1e-5;
    EXPECT_EQ(off, 0) << execution_form_name(form);
    double mean = 0;
    for (float x : m) mean += x;
    EXPECT_NEAR(mean / double(m.size()), 0.8, 0.01) << execution_form_name(form);
  }
}

// ---- a sun at 1e5 x the sky over a floor, against the closed form ----------------------------

// A Lambertian floor (two triangles, 40 units wide) seen straight down by an orthographic camera:
// with one bounce, every pixel's expectation is rho / pi x E, E the environment's irradiance on
// an upward surface, integrated here per texel in closed form (piecewise-constant radiance:
// the integral of cos(theta) sin(theta) over a texel's rows times its width in phi).
Scene floor_scene(const Environment& e, double albedo) {
  Scene scene;
  scene.file = "floor";
  scene.camera.position = {0, 5, 0};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 0, -1};
  scene.camera.projection = Projection::Orthographic;
  scene.camera.ortho_height = 4;
  TriangleMesh plane;
  plane.name = "floor";
  plane.positions = {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}};
  plane.triangles = {{0, 2, 1}, {0, 3, 2}};
  plane.material = lambertian(albedo);
  scene.meshes.push_back(plane);
  scene.environment = e;
  scene.settings.max_bounces = 1;
  return scene;
}

std::array<double, 3> floor_irradiance(const Environment& e) {
  std::array<double, 3> out{0, 0, 0};
  const int w = e.width, h = e.height;
  for (int row = 0; row < h / 2; ++row) {  // the upper hemisphere (h even: the horizon is an edge)
    const double t0 = kPi * row / h, t1 = kPi * (row + 1) / h;
    const double band = 0.5 * (std::sin(t1) * std::sin(t1) - std::sin(t0) * std::sin(t0)) * (2 * kPi / w);
    for (int col = 0; col < w; ++col)
      for (int c = 0; c < 3; ++c) out[c] += (*e.rgb)[3 * (size_t(row) * w + col) + c] * e.strength * band;
  }
  return out;
}

TEST(EnvironmentSun, FloorUnderASunOf1e5MatchesTheClosedFormWithoutFireflies) {
  const Environment e = sky(64, 32, 1e5, 3);
  const double albedo = 0.6;
  const std::array<double, 3> irradiance = floor_irradiance(e);
  const int w = 24, h = 24;
  Scene scene = floor_scene(e, albedo);
  scene.settings.estimator = "nee";
  for (const ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    const Film film = render(scene, w, h, 64, 21, form);
    const std::vector<float> m = film.mean_rgb(), v = film.variance_rgb();
    for (int c = 0; c < 3; ++c) {
      const double expected = albedo / kPi * irradiance[c];
      double sum = 0, sum_var = 0;
      for (int p = 0; p < w * h; ++p) {
        sum += m[3 * p + c];
        sum_var += v[3 * p + c];
        // No fireflies: each pixel's standard error at 64 spp stays below 5% of the value. (A
        // per-pixel z test would not be valid here: about 1.5% of the light samples go to the
        // sky and ground, whose light MIS gives to BSDF sampling, so such a sample brings nearly
        // nothing and a pixel's mean drops by 1/64 for each: a skewed, binomial-like spread that
        // the pixel's own variance estimate describes badly. The image mean below pools 36864
        // samples, where the normal approximation holds.)
        EXPECT_LT(std::sqrt(v[3 * p + c]), 0.05 * expected) << execution_form_name(form) << " pixel " << p;
      }
      const double mean = sum / (w * h), se = std::sqrt(sum_var) / (w * h);
      EXPECT_LE(std::fabs(mean - expected), 4 * se + 1e-5 * expected) << "channel " << c;
    }
  }
}

// The same floor by BSDF sampling alone (the book estimator) has the same expectation but a
// variance the sun dominates; next-event estimation with MIS cuts it by far more than its cost.
TEST(EnvironmentSun, MisIsFarLessNoisyThanBsdfSamplingAlone) {
  const Environment e = sky(64, 32, 1e5, 3);
  const int w = 24, h = 24;
  double variance[2] = {0, 0};
  int k = 0;
  for (const char* estimator : {"book", "nee"}) {
    Scene scene = floor_scene(e, 0.6);
    scene.settings.estimator = estimator;
    const Film film = render(scene, w, h, 64, 23);
    for (float x : film.variance_rgb()) variance[k] += x;
    ++k;
  }
  std::printf("floor under a 1e5 sun, summed variance of the pixel means at 64 spp: book %g, nee %g (%.0fx)\n",
              variance[0], variance[1], variance[0] / variance[1]);
  EXPECT_GT(variance[0], 100 * variance[1]);
}

// ---- MIS against BSDF sampling alone, with occlusion and interreflection ---------------------

// A ball on the floor under a sky with a mild sun (100 x the sky, large enough for BSDF sampling
// alone to converge), seen in perspective: the nee (MIS) and book (BSDF-only) images agree, block
// by block, within z of their combined standard errors.
TEST(EnvironmentMis, MisAndBsdfOnlyRendersAgree) {
  const Environment e = sky(32, 16, 100, 10);
  Scene scene = floor_scene(e, 0.6);
  scene.camera.projection = Projection::Perspective;
  scene.camera.position = {0, 2.5, 5};
  scene.camera.look_at = {0, 0.6, 0};
  scene.camera.up = {0, 1, 0};
  Sphere ball;
  ball.center = {0, 1, 0};
  ball.radius = 1;
  ball.material = lambertian(0.8);
  scene.spheres.push_back(ball);
  scene.settings.max_bounces = 3;
  const int w = 32, h = 24, block = 8;
  std::vector<float> mean[2], var[2];
  int k = 0;
  for (const char* estimator : {"book", "nee"}) {
    scene.settings.estimator = estimator;
    const Film film = render(scene, w, h, 256, 31 + k);
    mean[k] = film.mean_rgb();
    var[k] = film.variance_rgb();
    ++k;
  }
  const int blocks = (w / block) * (h / block);
  const double z = sidak_z(3 * blocks);
  for (int by = 0; by < h / block; ++by)
    for (int bx = 0; bx < w / block; ++bx)
      for (int c = 0; c < 3; ++c) {
        double diff = 0, v = 0;
        for (int y = by * block; y < (by + 1) * block; ++y)
          for (int x = bx * block; x < (bx + 1) * block; ++x) {
            const size_t i = 3 * (size_t(y) * w + x) + c;
            diff += mean[0][i] - mean[1][i];
            v += var[0][i] + var[1][i];
          }
        EXPECT_LE(std::fabs(diff), z * std::sqrt(v) + 1e-4 * block * block)
            << "block (" << bx << ", " << by << ") channel " << c;
      }
}

}  // namespace
}  // namespace clpt::test
