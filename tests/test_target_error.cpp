// --target-error keeps its promise: renders of the book's three scenes stopped by clpt's own error
// estimate (render/error_estimate.h) have a true relative error, against a reference with its
// own noise removed, between 0.6 and 1.2 times the target, for every sampler, with adaptive
// sampling off and on (render/adaptive_sampling.h), at targets of 10% and 5%. Small images (48x36), fixed seeds, next-event estimation (the first picture's
// estimator; the book's estimator at 10% too, where rare long paths carry the variance).
//
// References are rendered here, at the test's size, by clpt at many samples with the same pixel
// filter as the sampler under test: jitter and sobol converge to the pixel's box average, grid to
// the mean of its 16 fixed sub-pixel points. (The gemspt references of tests/reference/ are grid
// renders at 160x120: against them a jitter image keeps an MSE floor of 7e-4, about 8% relative,
// docs/sampler.md, so they cannot judge a 5% target. test_book_images.cpp ties clpt's images to
// them.) A reference's own noise is removed with its half-film estimate, which is unbiased:
// E[(x - ref)^2] = MSE(x) + MSE(ref) for independent x and ref.
//
// The bounds [0.6, 1.2] are the issue's. The estimate's own spread is far inside them: its mean
// squared error is a mean over 5184 pixel-channel terms (relative standard error about 2-3%), and
// the stopping rule's check points are at most 1/8 apart in samples (at most 6% in error).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <string>

#include "render/error_estimate.h"
#include "render/render_session.h"
#include "render_test_util.h"

namespace clpt::test {
namespace {

constexpr int kWidth = 48, kHeight = 36;

RenderRequest request_for(const std::string& scene_name, const std::string& estimator, Sampler sampler,
                          uint64_t seed) {
  RenderRequest request = scene_request(scene_name, kWidth, kHeight, seed, sampler);
  request.scene.settings.estimator = estimator;
  return request;
}

struct Reference {
  std::vector<float> mean;
  double mse = 0;         // its own estimated squared error, to subtract
  double image_mean = 0;  // over pixels and channels
};

// The reference of a scene for one pixel filter (grid: the grid sampler; else the box filter).
Reference render_reference(const std::string& scene_name, bool grid) {
  // Sobol for the box filter: at equal samples its error is a third to a half of jitter's, and its
  // half-film estimate overstates it, so subtracting it can only lower the true error measured.
  RenderRequest request = request_for(scene_name, "nee", grid ? Sampler::Grid : Sampler::Sobol, 99);
  request.scene.settings.spp = 4096;
  RenderReport report;
  const Film film = run_render(request, report);
  const ErrorEstimate e = estimate_error(film);
  EXPECT_TRUE(e.valid);
  return {film.mean_rgb(), e.mse, e.image_mean};
}

struct Case {
  const char* estimator;
  Sampler sampler;
  double target;
  bool adaptive;
};

// The render of `c` stopped at its target, judged against `ref`.
void expect_calibrated(const std::string& scene_name, const Case& c, const Reference& ref) {
  SCOPED_TRACE(scene_name + " " + c.estimator + " " + sampler_name(c.sampler) + " target " + std::to_string(c.target) +
               (c.adaptive ? " adaptive" : ""));
  RenderRequest request = request_for(scene_name, c.estimator, c.sampler, 2015);
  request.target_error = c.target;
  request.adaptive = c.adaptive;
  request.spp_given = false;
  RenderReport report;
  const Film film = run_render(request, report);
  ASSERT_EQ(report.stop, StopReason::TargetError);
  const std::vector<float> x = film.mean_rgb();
  double sq = 0;
  for (size_t i = 0; i < x.size(); ++i) sq += (double(x[i]) - ref.mean[i]) * (double(x[i]) - ref.mean[i]);
  const double true_mse = sq / double(x.size()) - ref.mse;
  const double true_relative = std::sqrt(std::max(0.0, true_mse)) / ref.image_mean;
  // The table of docs/target-error.md is this line (times: untimed by the test, only reported).
  std::printf("| %s | %s | %s%s | %.2f | %llu | %.3f s | %.4f | %.4f | %.4f | %.2f | %.1f%% |\n",
              scene_name.c_str(), c.estimator, sampler_name(c.sampler), c.adaptive ? ", adaptive" : "", c.target,
              (unsigned long long)film.samples_per_pixel(), report.render_seconds, report.estimate.relative_rmse,
              report.estimate.relative_rmse_upper, true_relative, true_relative / c.target,
              100 * ref.mse / std::pow(c.target * ref.image_mean, 2));
  EXPECT_GE(true_relative, 0.6 * c.target);
  EXPECT_LE(true_relative, 1.2 * c.target);
}

// Every sampler, adaptive off and on; next-event estimation at 10% and 5%, the book's estimator
// at 10%.
std::vector<Case> cases() {
  std::vector<Case> out;
  for (bool adaptive : {false, true})
    for (Sampler sampler : {Sampler::Jitter, Sampler::Sobol, Sampler::Grid}) {
      for (double target : {0.10, 0.05}) out.push_back({"nee", sampler, target, adaptive});
      out.push_back({"book", sampler, 0.10, adaptive});
    }
  return out;
}

// One process per scene (ctest runs each test alone): its two references are rendered once.
class TargetError : public ::testing::TestWithParam<std::string> {};

TEST_P(TargetError, TrueErrorIsBetween0p6And1p2TimesTheTarget) {
  const Reference box = render_reference(GetParam(), false), grid = render_reference(GetParam(), true);
  for (const Case& c : cases()) expect_calibrated(GetParam(), c, c.sampler == Sampler::Grid ? grid : box);
}

INSTANTIATE_TEST_SUITE_P(BookScenes, TargetError, ::testing::Values("diffuse", "specular", "glass"),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param; });

}  // namespace
}  // namespace clpt::test
