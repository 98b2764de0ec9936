// Punctual lights against closed forms, seen by an orthographic camera looking straight down at a
// Lambertian plane of albedo rho (plane_closed_form.h): a pixel's radiance is rho / pi times the
// irradiance averaged over the pixel's square of the plane. Point light: I cos / d^2; spot: times KHR_lights_punctual's cone ramp; directional: E
// cos; range: the window clamp(1 - (d / range)^4, 0, 1), and exactly 0 beyond the range. Each in
// the megakernel, the wavefront and the generic kernel; thresholds are z of each pixel's own
// variance (Sidak over the pixels) plus float rounding.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "plane_closed_form.h"
#include "render/render_session.h"
#include "util/error.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr int kSize = kPlaneImageSize;

// The plane (plane_closed_form.h) under `light`.
Scene plane_scene(const PunctualLight& light) {
  Scene scene = lit_plane_scene("punctual");
  scene.lights.push_back(light);
  return scene;
}

// Renders `light` above the plane in each form and compares every pixel with `irradiance`.
void expect_closed_form(const PunctualLight& light, const std::function<double(double, double)>& irradiance) {
  const PlaneExpected expected = expected_plane_image(irradiance);
  const int comparisons = kSize * kSize * int(std::size(kPlaneForms));
  for (const KernelForm& f : kPlaneForms) {
    SCOPED_TRACE(f.name);
    const int checked = expect_plane_matches(render_plane(plane_scene(light), f, 64, 3), expected, comparisons);
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
