#include "plane_closed_form.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mesh_test_util.h"
#include "render_test_util.h"

namespace clpt::test {

namespace {
constexpr double kPi = 3.14159265358979323846;
}

Scene lit_plane_scene(const std::string& file) {
  Scene scene;
  scene.file = file;
  scene.camera.position = {0, 5, 0};
  scene.camera.look_at = {0, 0, 0};
  scene.camera.up = {0, 0, -1};
  scene.camera.projection = Projection::Orthographic;
  scene.camera.ortho_height = kPlaneSensor;
  TriangleMesh plane;
  plane.name = "plane";
  plane.positions = {{-20, 0, -20}, {20, 0, -20}, {20, 0, 20}, {-20, 0, 20}};
  plane.triangles = {{0, 2, 1}, {0, 3, 2}};
  plane.material = lambertian(kPlaneAlbedo);
  scene.meshes.push_back(plane);
  scene.settings.estimator = "nee";
  scene.settings.max_bounces = 2;
  return scene;
}

PlaneExpected expected_plane_image(const std::function<double(double, double)>& irradiance) {
  constexpr int n = kPlaneImageSize;
  PlaneExpected out{std::vector<double>(n * n), std::vector<double>(n * n), std::vector<bool>(n * n)};
  constexpr int kSub = 16;
  for (int row = 0; row < n; ++row)
    for (int col = 0; col < n; ++col) {
      double sum = 0, lo = 1e300, hi = 0;
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const double fx = (col + (a + 0.5) / kSub) / n;
          const double fy = (n - 1 - row + (b + 0.5) / kSub) / n;
          const double e = irradiance((fx - 0.5) * kPlaneSensor, -(fy - 0.5) * kPlaneSensor);
          sum += e, lo = std::min(lo, e), hi = std::max(hi, e);
        }
      const int i = row * n + col;
      out.mean[i] = kPlaneAlbedo / kPi * sum / (kSub * kSub);
      out.brightest[i] = kPlaneAlbedo / kPi * hi;
      out.edge[i] = lo == 0 && hi > 0;
    }
  return out;
}

PlaneImage render_plane(const Scene& scene, const KernelForm& f, int64_t spp, uint64_t seed) {
  RenderRequest request = test_request(scene, kPlaneImageSize, kPlaneImageSize, spp, seed);
  request.form = f.form;
  request.generic_kernel = f.generic;
  RenderReport report;
  const Film film = run_render(request, report);
  return {film.mean_rgb(), film.variance_rgb()};
}

int expect_plane_matches(const PlaneImage& image, const PlaneExpected& expected, int comparisons) {
  constexpr int n = kPlaneImageSize;
  const double z = sidak_z(comparisons);
  int bad = 0, checked = 0;
  for (int i = 0; i < n * n; ++i) {
    const double m = image.mean[3 * i], e = expected.mean[i];
    if (e == 0) {
      if (m != 0.0 && bad++ < 5) ADD_FAILURE() << "pixel " << i % n << "," << i / n << ": " << m << ", expected 0";
      continue;
    }
    if (expected.edge[i]) {
      if ((m < 0 || m > expected.brightest[i] * (1 + 1e-4)) && bad++ < 5)
        ADD_FAILURE() << "pixel " << i % n << "," << i / n << " (on the lit region's edge): " << m << " outside [0, "
                      << expected.brightest[i] << "]";
      continue;
    }
    const double tolerance = z * std::sqrt(double(image.variance[3 * i])) + 2e-4 * e + 1e-7;
    if (std::fabs(m - e) > tolerance && bad++ < 5)
      ADD_FAILURE() << "pixel " << i % n << "," << i / n << ": " << m << " expected " << e << " +- " << tolerance;
    ++checked;
  }
  EXPECT_EQ(bad, 0) << "pixels off the closed form";
  return checked;
}

}  // namespace clpt::test
