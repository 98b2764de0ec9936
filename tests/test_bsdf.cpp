// Glass: exact unpolarised Fresnel at normal incidence and grazing, total internal reflection,
// and the refraction direction and radiance scale of the book's estimator.
#include <gtest/gtest.h>

#include <cmath>

#include "device_test_util.h"

namespace clpt::test {
namespace {

std::vector<float> fresnel(const std::vector<cl_float2>& eta_cos) {
  Kernel kernel(test_program("probe_stages.cl"), "probe_fresnel", test_device().where());
  Buffer in = upload(eta_cos);
  Buffer out(test_device(), eta_cos.size() * sizeof(float), CL_MEM_WRITE_ONLY, "fresnel");
  kernel.set_arg(0, in);
  kernel.set_arg(1, out);
  test_device().launch(kernel, eta_cos.size(), 0, "probe_fresnel");
  return download<float>(out, eta_cos.size());
}

// Textbook unpolarised Fresnel in double, for eta = n_from / n_to.
double fresnel_reference(double eta, double cos_i) {
  const double sin2_t = eta * eta * (1 - cos_i * cos_i);
  const double cos_t = std::sqrt(1 - sin2_t);
  const double n1 = eta, n2 = 1.0;  // only the ratio matters
  const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
  const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

TEST(Fresnel, NormalIncidenceIsFourPercentForGlass) {
  const auto f = fresnel({{{1.0f / 1.5f, 1.0f}}, {{1.5f, 1.0f}}});
  EXPECT_NEAR(f[0], 0.04, 1e-6);  // ((n1 - n2) / (n1 + n2))^2, entering
  EXPECT_NEAR(f[1], 0.04, 1e-6);  // and leaving
}

TEST(Fresnel, MatchesTextbookAtAllAngles) {
  std::vector<cl_float2> in;
  for (int i = 1; i <= 100; ++i) in.push_back({{1.0f / 1.5f, float(i) / 100.0f}});
  const auto f = fresnel(in);
  for (size_t i = 0; i < in.size(); ++i) EXPECT_NEAR(f[i], fresnel_reference(1 / 1.5, in[i].s[1]), 2e-6);
  EXPECT_NEAR(f[0], fresnel_reference(1 / 1.5, 0.01), 2e-6);
  EXPECT_GT(f[0], 0.9);  // grazing incidence reflects almost everything
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
  // Leaving glass (eta 1.5): critical cos_i = sqrt(1 - 1/1.5^2) = 0.7454.
  const auto f = fresnel({{{1.5f, 0.70f}}, {{1.5f, 0.80f}}});
  EXPECT_EQ(f[0], -1.0f);
  EXPECT_GT(f[1], 0.0f);
  EXPECT_LT(f[1], 1.0f);
}

struct GlassResult {
  cl_float4 dir, weight;
};

GlassResult glass(cl_float4 d, cl_float4 n, cl_float4 u) {
  Kernel kernel(test_program("probe_stages.cl"), "probe_glass", test_device().where());
  Buffer in = upload(std::vector<cl_float4>{d, n, u});
  Buffer out(test_device(), 2 * sizeof(cl_float4), CL_MEM_WRITE_ONLY, "glass");
  kernel.set_arg(0, in);
  kernel.set_arg(1, 1.5f);
  kernel.set_arg(2, out);
  test_device().launch(kernel, 1, 0, "probe_glass");
  const auto r = download<cl_float4>(out, 2);
  return {r[0], r[1]};
}

TEST(GlassSample, RefractsWithRadianceScaleAndReflectsWithFresnelProbability) {
  // Normal incidence from outside, u = 0.5 > Fr = 0.04: refracts straight on, weight (1/1.5)^2.
  const GlassResult in = glass({{0, 0, -1, 0}}, {{0, 0, 1, 0}}, {{0, 0, 0.5f, 0}});
  EXPECT_NEAR(in.dir.s[2], -1.0, 1e-6);
  EXPECT_NEAR(in.weight.s[0], 1 / 2.25, 1e-6);
  // u = 0.01 < Fr: mirror reflection, weight 1.
  const GlassResult refl = glass({{0, 0, -1, 0}}, {{0, 0, 1, 0}}, {{0, 0, 0.01f, 0}});
  EXPECT_NEAR(refl.dir.s[2], 1.0, 1e-6);
  EXPECT_NEAR(refl.weight.s[0], 1.0, 1e-6);
  // Leaving at 60 degrees from the normal (beyond the critical 41.8): total internal reflection.
  const float s = std::sqrt(3.0f) / 2;
  const GlassResult tir = glass({{s, 0, 0.5f, 0}}, {{0, 0, 1, 0}}, {{0, 0, 0.99f, 0}});
  EXPECT_NEAR(tir.dir.s[0], s, 1e-6);
  EXPECT_NEAR(tir.dir.s[2], -0.5, 1e-6);
  EXPECT_NEAR(tir.weight.s[0], 1.0, 1e-6);
  // Entering at 45 degrees: Snell, sin t = sin i / 1.5.
  const float h = std::sqrt(0.5f);
  const GlassResult snell = glass({{h, 0, -h, 0}}, {{0, 0, 1, 0}}, {{0, 0, 0.99f, 0}});
  EXPECT_NEAR(snell.dir.s[0], h / 1.5, 1e-6);
  EXPECT_NEAR(snell.dir.s[2], -std::sqrt(1 - 0.5 / 2.25), 1e-6);
}

}  // namespace
}  // namespace clpt::test
