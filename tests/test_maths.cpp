// The kernels' own replacements for library maths (kernels/maths.cl), against double precision:
// unit_circle for sin/cos and pow_unit for pow, both written so that PoCL can vectorise them.
#include <gtest/gtest.h>

#include <cmath>

#include "device_test_util.h"

namespace clpt::test {
namespace {

TEST(Maths, UnitCircleMatchesSinCos) {
  std::vector<float> u;
  for (int i = 0; i <= 100000; ++i) u.push_back(float(i) / 100000.0f);
  Kernel kernel(test_program("probe_stages.cl"), "probe_unit_circle", test_device().where());
  Buffer in = upload(u);
  Buffer out(test_device(), u.size() * sizeof(cl_float2), CL_MEM_WRITE_ONLY, "circle");
  kernel.set_arg(0, in);
  kernel.set_arg(1, out);
  test_device().launch(kernel, u.size(), 0, "probe_unit_circle");
  const auto cs = download<cl_float2>(out, u.size());
  double worst = 0;
  for (size_t i = 0; i < u.size(); ++i) {
    const double angle = 2 * 3.14159265358979323846 * double(u[i]);
    worst = std::max({worst, std::abs(cs[i].s[0] - std::cos(angle)), std::abs(cs[i].s[1] - std::sin(angle))});
  }
  EXPECT_LT(worst, 4e-7);
}

TEST(Maths, PowUnitMatchesPow) {
  std::vector<cl_float2> in;
  for (float a : {1.0f / 101.0f, 1.0f / 11.0f, 0.25f, 0.5f, 1.0f})
    for (int i = 0; i <= 20000; ++i) {
      const float u = i == 0 ? 0.0f : std::ldexp(float(i % 1000 + 1) / 1000.0f, -(i / 1000));
      in.push_back({{u, a}});
    }
  Kernel kernel(test_program("probe_stages.cl"), "probe_pow_unit", test_device().where());
  Buffer buf = upload(in);
  Buffer out(test_device(), in.size() * sizeof(float), CL_MEM_WRITE_ONLY, "pow");
  kernel.set_arg(0, buf);
  kernel.set_arg(1, out);
  test_device().launch(kernel, in.size(), 0, "probe_pow_unit");
  const auto p = download<float>(out, in.size());
  double worst = 0;
  for (size_t i = 0; i < in.size(); ++i) {
    const double ref = std::pow(double(in[i].s[0]), double(in[i].s[1]));
    if (ref == 0) {
      EXPECT_EQ(p[i], 0.0f);
      continue;
    }
    worst = std::max(worst, std::abs(p[i] - ref) / ref);
  }
  EXPECT_LT(worst, 1e-6);
}

}  // namespace
}  // namespace clpt::test
