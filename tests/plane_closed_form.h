// A Lambertian plane seen straight down by an orthographic camera, the set-up of the closed-form
// light tests (test_punctual_lights.cpp, test_normal_map_closed_form.cpp): a pixel's radiance is
// rho / pi times the irradiance averaged over the pixel's square of the plane, which the host
// integrates in double (16 x 16 points a pixel), and every pixel is checked against it with z of
// its own variance (Sidak over the comparisons) plus float rounding.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "render/render_request.h"
#include "scene/scene.h"

namespace clpt::test {

constexpr int kPlaneImageSize = 24;   // pixels a side
constexpr double kPlaneSensor = 6.0;  // the orthographic sensor's side, world units
constexpr double kPlaneAlbedo = 0.6;

// The plane y = 0 (two triangles, 40 units wide, Lambertian of kPlaneAlbedo, no light) under an
// orthographic camera at y = 5 whose image's right is +x and whose image's up is -z; estimator
// nee, 2 bounces. `file` names the scene in messages.
Scene lit_plane_scene(const std::string& file);

// Radiance of each pixel (row-major) for irradiance e(x, z) at the plane's point (x, 0, z), the
// pixel's brightest point, and whether the lit region's edge crosses the pixel (lit at some of its
// points, dark at others: there the samples may all miss the lit part and the pixel's variance
// says nothing, so only 0 <= mean <= brightest is checked).
struct PlaneExpected {
  std::vector<double> mean, brightest;
  std::vector<bool> edge;
};
PlaneExpected expected_plane_image(const std::function<double(double, double)>& irradiance);

// The kernels a closed-form test renders with.
struct KernelForm {
  const char* name;
  ExecutionForm form;
  bool generic;
};
constexpr KernelForm kMegakernelForm{"megakernel", ExecutionForm::Megakernel, false};
constexpr KernelForm kPlaneForms[] = {kMegakernelForm,
                                      {"wavefront", ExecutionForm::Wavefront, false},
                                      {"generic megakernel", ExecutionForm::Megakernel, true}};

struct PlaneImage {
  std::vector<float> mean, variance;  // RGB interleaved
};
// `scene` at kPlaneImageSize square, `spp`, `seed`, in form `f`, on the test device (CLPT_TEST_DEVICE,
// else "cpu"), clpt's kernel cache off.
PlaneImage render_plane(const Scene& scene, const KernelForm& f, int64_t spp, uint64_t seed);

// Every pixel of `image` against `expected`: pixels the closed form says are dark exactly 0, those
// the lit region's edge crosses within [0, brightest], the others within z of their own variance
// (Sidak over `comparisons`) plus 2e-4 relative and 1e-7. Returns how many lit pixels were checked.
int expect_plane_matches(const PlaneImage& image, const PlaneExpected& expected, int comparisons);

}  // namespace clpt::test
