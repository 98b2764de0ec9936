// Watchdog-sized launches and resumed renders give the image of a plain render (same device and
// seed): pixel ranges do not change any pixel's sums, so a single pass split into many launches
// is bit-identical; a resumed render may split passes differently, so it agrees to float rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <utility>

#include "render_test_util.h"

namespace clpt::test {
namespace {

RenderRequest small_request(ExecutionForm form, Sampler sampler, int64_t spp) {
  RenderRequest request = test_request(load_book_scene("glass"), 64, 48, spp, 5, sampler);
  request.form = form;
  return request;
}

TEST(Launches, ManySmallLaunchesEqualOneLaunch) {
  // Grid sampler, 16 spp: exactly one pass, so only the launch split differs.
  RenderRequest one = small_request(ExecutionForm::Megakernel, Sampler::Grid, 16);
  one.launch_target_s = 0;
  RenderRequest many = one;
  many.launch_target_s = 1e-4;  // --launch-ms 0.1: a few hundred pixels per launch on PoCL
  RenderReport r1, r2;
  const Film a = run_render(one, r1);
  const Film b = run_render(many, r2);
  ASSERT_EQ(r1.passes, 1);
  ASSERT_EQ(r2.passes, 1);
  EXPECT_EQ(r1.launches, 1u);
  EXPECT_GT(r2.launches, 4u);  // split for sure, however fast the device
  EXPECT_EQ(a.sums(), b.sums());
  EXPECT_EQ(a.sums_of_squares(), b.sums_of_squares());
  EXPECT_EQ(a.valid_counts(), b.valid_counts());
  EXPECT_EQ(b.samples_per_pixel(), 16u);
}

// A render resumed from its own 12-spp film and continued to 40 spp, and the same render straight
// to 40 spp: {resumed, straight}.
std::pair<Film, Film> resumed_and_straight(ExecutionForm form, Sampler sampler) {
  RenderReport r1, r2, r3;
  RenderRequest second = small_request(form, sampler, 40);
  second.resume = run_render(small_request(form, sampler, 12), r1);
  Film resumed = run_render(second, r2);
  return {std::move(resumed), run_render(small_request(form, sampler, 40), r3)};
}

TEST(Launches, ResumedRenderEqualsStraightRender) {
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    const auto [resumed, straight] = resumed_and_straight(form, Sampler::Jitter);
    ASSERT_EQ(resumed.samples_per_pixel(), 40u);
    EXPECT_EQ(resumed.total_samples(), straight.total_samples());
    EXPECT_EQ(resumed.valid_counts(), straight.valid_counts());
    const auto& a = resumed.sums();
    const auto& b = straight.sums();
    for (size_t i = 0; i < a.size(); ++i)
      ASSERT_NEAR(a[i], b[i], 1e-5 * std::max(std::abs(b[i]), 1e-3)) << "value " << i;
  }
}

// A Sobol render resumed at 12 samples (so its passes split differently) gives the image of a
// straight one: each sample's points depend on its index, not on the pass that traced it.
TEST(Launches, SobolResumedRenderEqualsStraightRender) {
  for (ExecutionForm form : {ExecutionForm::Megakernel, ExecutionForm::Wavefront}) {
    SCOPED_TRACE(execution_form_name(form));
    const auto [resumed, straight] = resumed_and_straight(form, Sampler::Sobol);
    ASSERT_EQ(resumed.samples_per_pixel(), 40u);
    EXPECT_EQ(resumed.valid_counts(), straight.valid_counts());
    expect_same_image(resumed.mean_rgb(), straight.mean_rgb());
  }
}

}  // namespace
}  // namespace clpt::test
