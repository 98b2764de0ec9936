// Execution forms and kernel variants agree on the same device and seed: the megakernel and the
// wavefront (with few or many paths in flight), and the scene-specialised and generic kernels,
// give the same image up to float rounding, as do two work-group sizes (a different contraction of a*b+c can send a rare path
// elsewhere, hence the 99% criterion rather than 100%).
#include <gtest/gtest.h>

#include <cmath>

#include "device_test_util.h"
#include "render_test_util.h"

namespace clpt::test {
namespace {

struct Variant {
  ExecutionForm form = ExecutionForm::Megakernel;
  uint32_t paths_in_flight = 0;
  bool generic = false;
  size_t local_size = 0;  // 0: the form's default
};

std::vector<float> render_variant(const std::string& scene_name, const Variant& v) {
  RenderRequest request;
  request.use_kernel_cache = false;  // tests compile the kernels under test from source
  request.scene = load_book_scene(scene_name);
  request.scene.settings.width = 48;
  request.scene.settings.height = 36;
  request.scene.settings.spp = 32;
  request.scene.settings.seed = 77;
  request.scene.settings.sampler = Sampler::Jitter;
  const char* device = std::getenv("CLPT_TEST_DEVICE");
  request.device = device ? device : "cpu";
  request.form = v.form;
  request.paths_in_flight = v.paths_in_flight;
  request.generic_kernel = v.generic;
  request.local_size = v.local_size;
  RenderReport report;
  return run_render(request, report).mean_rgb();
}

// Means within 1e-4 relative and >= 99% of values within 1e-4 relative.
void expect_same_image(const std::vector<float>& a, const std::vector<float>& b) {
  ASSERT_EQ(a.size(), b.size());
  double sum_a = 0, sum_b = 0;
  size_t close = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sum_a += a[i];
    sum_b += b[i];
    close += std::abs(a[i] - b[i]) <= 1e-4 * std::max({std::abs(a[i]), std::abs(b[i]), 1e-6f});
  }
  EXPECT_NEAR(sum_a, sum_b, 1e-4 * sum_a);
  EXPECT_GE(double(close), 0.99 * double(a.size())) << close << " of " << a.size();
}

class FormsAgree : public ::testing::TestWithParam<std::string> {};

TEST_P(FormsAgree, MegakernelEqualsWavefront) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Megakernel}),
                    render_variant(GetParam(), {ExecutionForm::Wavefront}));
}

TEST_P(FormsAgree, WavefrontWith64PathsInFlightEqualsDefault) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Wavefront, 64}),
                    render_variant(GetParam(), {ExecutionForm::Wavefront, 0}));
}

TEST_P(FormsAgree, SpecialisedKernelEqualsGeneric) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false}),
                    render_variant(GetParam(), {ExecutionForm::Megakernel, 0, true}));
}

TEST_P(FormsAgree, TwoWorkGroupSizesGiveTheSameImage) {
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 8}),
                    render_variant(GetParam(), {ExecutionForm::Megakernel, 0, false, 64}));
  expect_same_image(render_variant(GetParam(), {ExecutionForm::Wavefront, 0, false, 32}),
                    render_variant(GetParam(), {ExecutionForm::Wavefront, 0, false, 128}));
}

INSTANTIATE_TEST_SUITE_P(BookScenes, FormsAgree, ::testing::Values("diffuse", "specular", "glass"));

}  // namespace
}  // namespace clpt::test
