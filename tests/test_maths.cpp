// The kernels' own replacements for library maths (kernels/maths.cl), against the host's libm:
// unit_circle for sin/cos and pow_unit for pow, both written so that PoCL can vectorise them, in
// float (fast and robust) and in double (the double preset); clpt_udiv for integer division.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "device_test_util.h"

namespace clpt::test {
namespace {

TEST(Maths, UnitCircleMatchesSinCos) {
  std::vector<float> u;
  for (int i = 0; i <= 100000; ++i) u.push_back(float(i) / 100000.0f);
  const auto cs = run_probe<cl_float2>("probe_unit_circle", u.size(), upload(u));
  double worst = 0;
  for (size_t i = 0; i < u.size(); ++i) {
    const double angle = 2 * 3.14159265358979323846 * double(u[i]);
    worst = std::max({worst, std::abs(cs[i].s[0] - std::cos(angle)), std::abs(cs[i].s[1] - std::sin(angle))});
  }
  EXPECT_LT(worst, 4e-7);
}

// clpt_udiv is exact over its whole contract (a below 2^31, b in [1, 2^30)): the quotients at and
// beside multiples of b, where a float estimate rounds across them, the largest a, and random pairs; with
// fast maths too (the fast preset's build option), whose float division may be approximate.
TEST(Maths, UdivIsExactIntegerDivision) {
  std::vector<cl_uint2> in;
  std::mt19937 rng(12345);
  const std::vector<uint32_t> divisors = {1u, 2u, 3u, 7u, 64u, 640u, 641u, 4095u, 65536u, 307200u,
                                          8388607u, 8388608u, 16777217u, (1u << 30) - 1u};
  for (uint32_t b : divisors) {
    const uint64_t top = 0x7fffffffull;
    for (uint64_t k : {uint64_t(0), uint64_t(1), uint64_t(2), uint64_t(1000), uint64_t(1) << 22, uint64_t(1) << 23,
                       uint64_t(1) << 24, top / b - 1, top / b})
      for (int64_t d : {-1, 0, 1})
        if (const int64_t a = int64_t(k * b) + d; a >= 0 && uint64_t(a) <= top) in.push_back({{cl_uint(a), b}});
    in.push_back({{cl_uint(top), b}});
    for (int i = 0; i < 200; ++i) in.push_back({{cl_uint(rng() >> 1), b}});
  }
  for (int i = 0; i < 20000; ++i) in.push_back({{cl_uint(rng() >> 1), cl_uint(rng() % ((1u << 30) - 1u) + 1u)}});
  for (const char* options : {"-cl-std=CL1.2", "-cl-std=CL1.2 -cl-unsafe-math-optimizations"}) {
    const auto q = run_probe_built<cl_uint>(options, "probe_udiv", in.size(), upload(in));
    size_t wrong = 0;
    for (size_t i = 0; i < in.size(); ++i)
      if (q[i] != in[i].s[0] / in[i].s[1] && wrong++ < 5)
        ADD_FAILURE() << options << ": " << in[i].s[0] << " / " << in[i].s[1] << " gave " << q[i];
    EXPECT_EQ(wrong, 0u) << options << ", of " << in.size();
  }
}

TEST(Maths, PowUnitMatchesPow) {
  std::vector<cl_float2> in;
  for (float a : {1.0f / 101.0f, 1.0f / 11.0f, 0.25f, 0.5f, 1.0f})
    for (int i = 0; i <= 20000; ++i) {
      const float u = i == 0 ? 0.0f : std::ldexp(float(i % 1000 + 1) / 1000.0f, -(i / 1000));
      in.push_back({{u, a}});
    }
  const auto p = run_probe<float>("probe_pow_unit", in.size(), upload(in));
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

// The double preset's polynomials (to x^17/x^18 for sin/cos, f^21 and z^17 for pow; maths.cl)
// must be as good as the library they replaced: within a few units in the last place of double.
constexpr const char* kDoubleOptions = "-cl-std=CL1.2 -DCLPT_PRECISION=2";

TEST(Maths, UnitCircleMatchesSinCosInDouble) {
  if (!test_device().device().fp64) GTEST_SKIP() << "the test device has no fp64";
  std::vector<double> u;
  for (int i = 0; i <= 100000; ++i) u.push_back(double(i) / 100000.0);
  Kernel kernel(test_program("probe_maths.cl", kDoubleOptions), "probe_unit_circle_real", test_device().where());
  Buffer in = upload(u);
  Buffer out(test_device(), 2 * u.size() * sizeof(double), CL_MEM_WRITE_ONLY, "circle");
  kernel.set_arg(0, in);
  kernel.set_arg(1, out);
  test_device().launch(kernel, u.size(), 0, "probe_unit_circle_real");
  const auto cs = download<double>(out, 2 * u.size());
  double worst = 0;
  for (size_t i = 0; i < u.size(); ++i) {
    const double angle = 2 * 3.14159265358979323846 * u[i];
    worst = std::max({worst, std::abs(cs[2 * i] - std::cos(angle)), std::abs(cs[2 * i + 1] - std::sin(angle))});
  }
  // The float version's bound is 4e-7; PoCL measures 7.2e-16 here, about 3 units in the last place
  // of 1 (2.2e-16); 2e-15 leaves room for a device that contracts the polynomials differently.
  EXPECT_LT(worst, 2e-15);
}

TEST(Maths, PowUnitMatchesPowInDouble) {
  if (!test_device().device().fp64) GTEST_SKIP() << "the test device has no fp64";
  std::vector<double> in;
  for (double a : {1.0 / 101.0, 1.0 / 11.0, 0.25, 0.5, 1.0, 7.0, 100.0})
    for (int i = 0; i <= 20000; ++i) {
      in.push_back(i == 0 ? 0.0 : std::ldexp(double(i % 1000 + 1) / 1000.0, -(i / 1000)));
      in.push_back(a);
    }
  const size_t n = in.size() / 2;
  Kernel kernel(test_program("probe_maths.cl", kDoubleOptions), "probe_pow_unit_real", test_device().where());
  Buffer buf = upload(in);
  Buffer out(test_device(), n * sizeof(double), CL_MEM_WRITE_ONLY, "pow");
  kernel.set_arg(0, buf);
  kernel.set_arg(1, out);
  test_device().launch(kernel, n, 0, "probe_pow_unit_real");
  const auto p = download<double>(out, n);
  double worst = 0;
  for (size_t i = 0; i < n; ++i) {
    const double ref = std::pow(in[2 * i], in[2 * i + 1]);
    if (ref < 0x1p-1000) {  // near double's smallest normal, where pow_unit flushes to 0
      EXPECT_LT(p[i], 0x1p-1000) << "u " << in[2 * i] << " a " << in[2 * i + 1];
      continue;
    }
    worst = std::max(worst, std::abs(p[i] - ref) / ref);
  }
  // a log2(u) reaches -2000 here, and its rounding (2000 * 2^-53, times ln 2) sets the relative
  // error: PoCL measures 9.8e-14.
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace clpt::test
