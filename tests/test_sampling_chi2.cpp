// Chi-square goodness of fit of the direction samplers the renderer uses (pbrt-v4 / Mitsuba 3
// recipe, docs/numerics.md): 1e6 samples from the device into (theta, phi) bins, expected counts from
// the analytic pdf integrated over each bin, cells with expected count < 5 pooled, alpha 0.01
// Sidak-corrected over the tests in this file.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "device_test_util.h"
#include "stat_test_util.h"

namespace clpt::test {
namespace {

constexpr int kSamples = 1000000;
constexpr int kThetaBins = 80, kPhiBins = 160;
constexpr int kTestsInFile = 3;
constexpr double kPi = 3.14159265358979323846;

std::vector<cl_float4> sample_directions(cl_uint mode, float exponent, cl_uint seed) {
  Kernel kernel(test_program("probe_stages.cl"), "probe_sample_directions", test_device().where());
  Buffer out(test_device(), kSamples * sizeof(cl_float4), CL_MEM_WRITE_ONLY, "directions");
  kernel.set_arg(0, mode);
  kernel.set_arg(1, exponent);
  kernel.set_arg(2, seed);
  kernel.set_arg(3, cl_uint(0));
  kernel.set_arg(4, out);
  test_device().launch(kernel, kSamples, 0, "probe_sample_directions");
  return download<cl_float4>(out, kSamples);
}

// mass_above(c): probability that cos(theta) >= c under the claimed pdf. Bins are uniform
// in cos(theta) over [0, 1] and in phi; the pdf is rotationally symmetric around +z.
double chi2_p_value(const std::vector<cl_float4>& dirs, const std::function<double(double)>& mass_above) {
  std::vector<double> observed(kThetaBins * kPhiBins, 0.0), expected(kThetaBins * kPhiBins, 0.0);
  for (const cl_float4& d : dirs) {
    const double c = std::clamp<double>(d.s[2], 0.0, 1.0 - 1e-12);
    double phi = std::atan2(d.s[1], d.s[0]);
    if (phi < 0) phi += 2 * kPi;
    const int ti = std::min(kThetaBins - 1, int(c * kThetaBins));
    const int pi = std::min(kPhiBins - 1, int(phi / (2 * kPi) * kPhiBins));
    observed[ti * kPhiBins + pi] += 1;
  }
  for (int t = 0; t < kThetaBins; ++t) {
    const double mass = mass_above(double(t) / kThetaBins) - mass_above(double(t + 1) / kThetaBins);
    for (int p = 0; p < kPhiBins; ++p) expected[t * kPhiBins + p] = mass / kPhiBins * kSamples;
  }
  return chi2_pooled_p_value(observed, expected);  // cells expecting fewer than 5 pooled
}

double sidak_alpha() { return 1 - std::pow(1 - 0.01, 1.0 / kTestsInFile); }

TEST(SamplingChi2, CosineHemisphere) {
  const auto dirs = sample_directions(0, 0, 1234);
  // pdf cos(theta)/pi: cos^2(theta) is uniform, so the mass with cos(theta) >= c is 1 - c^2.
  const double p = chi2_p_value(dirs, [](double c) { return 1 - c * c; });
  EXPECT_GT(p, sidak_alpha()) << "p-value " << p;
}

TEST(SamplingChi2, PhongLobeExponent100) {
  const auto dirs = sample_directions(1, 100.0f, 99);
  // pdf (n+1)/(2 pi) cos^n: P(cos alpha <= c) = c^(n+1).
  const double p = chi2_p_value(dirs, [](double c) { return 1 - std::pow(c, 101.0); });
  EXPECT_GT(p, sidak_alpha()) << "p-value " << p;
}

TEST(SamplingChi2, PhongLobeExponent3) {
  const auto dirs = sample_directions(1, 3.0f, 7);
  const double p = chi2_p_value(dirs, [](double c) { return 1 - std::pow(c, 4.0); });
  EXPECT_GT(p, sidak_alpha()) << "p-value " << p;
}

// The test can fail: a distribution slightly off the claimed one (cos^1.1 tested as cos^1) is
// rejected.
TEST(SamplingChi2, RejectsAWrongDistribution) {
  const auto dirs = sample_directions(1, 1.1f, 5);  // cos^1.1, not cos^1
  const double p = chi2_p_value(dirs, [](double c) { return 1 - c * c; });
  EXPECT_LT(p, 1e-6) << "p-value " << p;
}

}  // namespace
}  // namespace clpt::test
