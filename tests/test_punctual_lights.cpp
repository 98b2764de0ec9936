// Punctual lights against closed forms, seen by an orthographic camera looking straight down at a
// Lambertian plane of albedo rho: a pixel's radiance is rho / pi times the irradiance averaged
// over the pixel's square of the plane, which the host integrates in double (16 x 16 points per
// pixel). Point light: I cos / d^2; spot: times KHR_lights_punctual's cone ramp; directional: E
// cos; range: the window clamp(1 - (d / range)^4, 0, 1), and exactly 0 beyond the range. Each in
// the megakernel, the wavefront and the generic kernel; thresholds are z of each pixel's own
// variance (Sidak over the pixels) plus float rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "device_test_util.h"
#include "mesh_test_util.h"
#include "render_test_util.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = 24;           // pixels per side
constexpr double kHeight = 6.0;     // the orthographic sensor's side, world units
constexpr double kAlbedo = 0.6;

// The plane y = 0 (two triangles, 40 units wide) under an orthographic camera at y = 5 whose
// image's right is +x and whose image's up is -z.
Scene plane_scene(const PunctualLight& light) {
  Scene scene;
  scene.file = "punctual";
  scene.camera.position = {0, 5, 0};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 0, -1};
  scene.camera.projection = Projection::Orthographic;
  scene.camera.ortho_height = kHeight;
  TriangleMesh plane;
  plane.name = "plane";
  plane.positions = {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}};
  plane.triangles = {{0, 2, 1}, {0, 3, 2}};
  plane.material = lambertian(kAlbedo);
  scene.meshes.push_back(plane);
  scene.lights.push_back(light);
  scene.settings.estimator = "nee";
  scene.settings.max_bounces = 2;
  return scene;
}

// Radiance of each pixel (row-major), the plane's point (x, 0, z) lit with irradiance e(x, z),
// and whether the lit region's edge crosses the pixel (lit at some of its points, dark at
// others): there 64 samples may all miss the lit part, and the pixel's variance estimate says
// nothing, so only 0 <= mean <= the pixel's brightest point is checked.
struct Expected {
  std::vector<double> mean, brightest;
  std::vector<bool> edge;
};
Expected expected_image(const std::function<double(double, double)>& irradiance) {
  Expected out{std::vector<double>(kSize * kSize), std::vector<double>(kSize * kSize), std::vector<bool>(kSize * kSize)};
  constexpr int kSub = 16;
  for (int row = 0; row < kSize; ++row)
    for (int col = 0; col < kSize; ++col) {
      double sum = 0, lo = 1e300, hi = 0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const double fx = (col + (a + 0.5) / kSub) / kSize;
          const double fy = (kSize - 1 - row + (b + 0.5) / kSub) / kSize;
          const double e = irradiance((fx - 0.5) * kHeight, -(fy - 0.5) * kHeight);
          sum += e, lo = std::min(lo, e), hi = std::max(hi, e);
        }
      const int i = row * kSize + col;
      out.mean[i] = kAlbedo / kPi * sum / (kSub * kSub);
      out.brightest[i] = kAlbedo / kPi * hi;
      out.edge[i] = lo == 0 && hi > 0;
    }
  return out;
}

struct Form {
  const char* name;
  ExecutionForm form;
  bool generic;
};
constexpr Form kForms[] = {{"megakernel", ExecutionForm::Megakernel, false},
                           {"wavefront", ExecutionForm::Wavefront, false},
                           {"generic megakernel", ExecutionForm::Megakernel, true}};

// Renders `light` above the plane in each form and compares every pixel with `irradiance`.
void expect_closed_form(const PunctualLight& light, const std::function<double(double, double)>& irradiance) {
  const Expected expected = expected_image(irradiance);
  const double z = sidak_z(kSize * kSize * int(std::size(kForms)));
  for (const Form& f : kForms) {
    SCOPED_TRACE(f.name);
    Scene scene = plane_scene(light);
    scene.settings.width = scene.settings.height = kSize;
    scene.settings.spp = 64;
    scene.settings.seed = 3;
    RenderRequest request;
    request.use_kernel_cache = false;
    request.scene = scene;
    request.form = f.form;
    request.generic_kernel = f.generic;
    const char* device = std::getenv("CLPT_TEST_DEVICE");
    request.device = device ? device : "cpu";
    RenderReport report;
    const Film film = run_render(request, report);
    const auto mean = film.mean_rgb(), var = film.variance_rgb();
    int bad = 0, checked = 0;
    for (int i = 0; i < kSize * kSize; ++i) {
      const double m = mean[3 * i], e = expected.mean[i];
      if (e == 0) {
        EXPECT_EQ(m, 0.0) << "pixel " << i % kSize << "," << i / kSize << " lies beyond the light";
      }
      if (expected.edge[i]) {
        EXPECT_GE(m, 0.0);
        EXPECT_LE(m, expected.brightest[i] * (1 + 1e-4));
        continue;
      }
      const double tolerance = z * std::sqrt(double(var[3 * i])) + 2e-4 * e + 1e-7;
      if (std::fabs(m - e) > tolerance && bad++ < 5)
        ADD_FAILURE() << "pixel " << i % kSize << "," << i / kSize << ": " << m << " expected " << e << " +- "
                      << tolerance;
      checked += e > 0;
    }
    EXPECT_GT(checked, kSize * kSize / 8);  // the light reaches much of the image
  }
}

PunctualLight point_light(double height, double intensity) {
  PunctualLight l;
  l.name = "point";
  l.type = LightType::Point;
  l.position = {0.4, height, -0.3};
  l.intensity = {intensity, intensity, intensity};
  return l;
}

// I cos / d^2 with cos = h / d.
double point_irradiance(const PunctualLight& l, double x, double z) {
  const double dx = x - l.position[0], dz = z - l.position[2], h = l.position[1];
  const double d2 = dx * dx + dz * dz + h * h;
  return l.intensity[0] * h / (d2 * std::sqrt(d2));
}

TEST(PunctualLights, PointLightGivesIntensityTimesCosineOverDistanceSquared) {
  const PunctualLight l = point_light(1.5, 3.0);
  expect_closed_form(l, [&](double x, double z) { return point_irradiance(l, x, z); });
}

TEST(PunctualLights, SpotLightFollowsTheConeRamp) {
  PunctualLight l = point_light(2.0, 5.0);
  l.type = LightType::Spot;
  l.direction = {0, -1, 0};
  l.inner_cone_rad = 20 * kPi / 180;
  l.outer_cone_rad = 40 * kPi / 180;
  const double cos_inner = std::cos(l.inner_cone_rad), cos_outer = std::cos(l.outer_cone_rad);
  expect_closed_form(l, [&](double x, double z) {
    const double dx = x - l.position[0], dz = z - l.position[2], h = l.position[1];
    const double c = h / std::sqrt(dx * dx + dz * dz + h * h);  // the angle from the spot's axis
    const double ramp = std::clamp((c - cos_outer) / (cos_inner - cos_outer), 0.0, 1.0);
    return point_irradiance(l, x, z) * ramp * ramp;
  });
}

TEST(PunctualLights, DirectionalLightGivesIrradianceTimesCosine) {
  PunctualLight l;
  l.name = "sun";
  l.type = LightType::Directional;
  l.direction = {0.6, -0.8, 0};  // cos 0.8 on the plane
  l.intensity = {1.25, 1.25, 1.25};
  expect_closed_form(l, [](double, double) { return 1.25 * 0.8; });
}

TEST(PunctualLights, RangeWindowsTheLightAndCutsItOff) {
  PunctualLight l = point_light(1.0, 2.0);
  l.range = 2.5;  // reaches the plane out to a radius of sqrt(2.5^2 - 1) = 2.29
  expect_closed_form(l, [&](double x, double z) {
    const double dx = x - l.position[0], dz = z - l.position[2], h = l.position[1];
    const double d = std::sqrt(dx * dx + dz * dz + h * h);
    const double q = std::pow(d / l.range, 4);
    return point_irradiance(l, x, z) * std::max(0.0, 1 - q);
  });
}

// The book estimator cannot see a delta light: the plan refuses it, naming the light.
TEST(PunctualLights, BookEstimatorIsRefused) {
  Scene scene = plane_scene(point_light(1, 1));
  scene.settings.estimator = "book";
  RenderRequest request;
  request.scene = scene;
  request.device = "cpu";
  try {
    RenderReport report;
    run_render(request, report);
    FAIL() << "rendered";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ExitCode::Usage);
    EXPECT_NE(std::string(e.what()).find("point: a point light is a delta light"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace clpt::test
