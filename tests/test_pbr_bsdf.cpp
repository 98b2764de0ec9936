// The Pbr material (kernels/bsdf_pbr.cl) on the device, tested as pbrt's and Mitsuba's suites
// test a BSDF: reciprocity and f >= 0 at random pairs; the white furnace (metallic 1, base colour
// 1) against the directional albedo integrated on the host in double; albedo <= 1 for metals and
// dielectrics; the sampler's density integrating to the share of samples it keeps; and a
// chi-square test of the sampled directions against that density. Fixed seeds; thresholds from
// each estimate's own standard error.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "device_test_util.h"
#include "stat_test_util.h"

namespace clpt::test {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Pbr {
  float base = 1, metallic = 1, roughness = 0.5f, ior = 1.5f, transmission = 0;
  float volume = 0;  // 0 thin-walled, 1 a volume entered, 2 a volume left (probe_pbr)
};

struct ProbeOut {
  cl_float4 sampled, weight, eval;
};

// Runs probe_pbr on pairs (wo, u): u is the sampler's uniforms and, read as a direction, where
// the material is evaluated.
std::vector<ProbeOut> probe(const Pbr& m, const std::vector<cl_float4>& pairs) {
  const cl_float4 params{{m.base, m.base, m.base, m.metallic}};
  const cl_float4 shape{{m.roughness, m.ior, m.transmission, m.volume}};
  const size_t n = pairs.size() / 2;
  return run_probe<ProbeOut>("probe_pbr", n, params, shape, upload(pairs));
}

cl_float4 direction(double cos_theta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
  return {{float(s * std::cos(phi)), float(s * std::sin(phi)), float(cos_theta), 0}};
}

// n samples at wo = (sin, 0, cos) with uniforms from a fixed seed.
std::vector<ProbeOut> sample(const Pbr& m, double cos_o, size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0, 1);
  std::vector<cl_float4> pairs;
  pairs.reserve(2 * n);
  for (size_t i = 0; i < n; ++i) {
    pairs.push_back(direction(cos_o, 0));
    pairs.push_back({{u(rng), u(rng), u(rng), u(rng)}});
  }
  return probe(m, pairs);
}

// Mean and standard error of the samples' weight (channel 0): the directional albedo.
std::pair<double, double> mc_albedo(const std::vector<ProbeOut>& s) {
  double sum = 0, sum2 = 0;
  for (const ProbeOut& o : s) sum += o.weight.s[0], sum2 += double(o.weight.s[0]) * o.weight.s[0];
  const double n = double(s.size()), mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

// The white metal's albedo, f = D V Schlick(1) = D V, integrated in double over the half vector
// (theta_h = atan(alpha tan(v pi / 2)) spreads the grid by the lobe's width).
double white_metal_albedo(double cos_o, double roughness, int n = 600) {
  const double alpha = std::max(roughness * roughness, 1e-4), a2 = alpha * alpha;
  const double so = std::sqrt(1 - cos_o * cos_o);
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    const double v = (i + 0.5) / n, tv = std::tan(v * kPi / 2);
    const double th = std::atan(alpha * tv), cv = std::cos(v * kPi / 2);
    const double dth = alpha * (kPi / 2) / (cv * cv) / (1 + a2 * tv * tv) / n;
    for (int j = 0; j < 2 * n; ++j) {
      const double ph = (j + 0.5) / (2 * n) * 2 * kPi;
      const double h[3] = {std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)};
      const double oh = h[0] * so + h[2] * cos_o;
      if (oh <= 0) continue;
      const double ci = 2 * oh * h[2] - cos_o;
      if (ci <= 0) continue;
      const double k = h[2] * h[2] * (a2 - 1) + 1, d = a2 / (kPi * k * k);
      const double vis = 0.5 / (ci * std::sqrt(a2 + (1 - a2) * cos_o * cos_o) + cos_o * std::sqrt(a2 + (1 - a2) * ci * ci));
      sum += d * vis * ci * 4 * oh * std::sin(th) * dth * (kPi / n);  // d omega_i = 4 (o.h) d omega_h
    }
  }
  return sum;
}

TEST(PbrBsdf, WhiteFurnaceMatchesTheAlbedoIntegratedOnTheHost) {
  const Pbr metal;  // metallic 1, base 1
  unsigned seed = 1;
  for (float roughness : {0.1f, 0.3f, 0.6f, 1.0f})
    for (double cos_o : {1.0, 0.7, 0.3, 0.1}) {
      Pbr m = metal;
      m.roughness = roughness;
      const auto [mean, error] = mc_albedo(sample(m, cos_o, 200000, seed++));
      const double reference = white_metal_albedo(cos_o, roughness);
      EXPECT_NEAR(mean, reference, 4 * error + 2e-3) << "roughness " << roughness << ", cos " << cos_o;
      EXPECT_LE(reference, 1 + 1e-6);
    }
}

TEST(PbrBsdf, AlbedoIsAtMostOne) {
  unsigned seed = 100;
  for (float metallic : {0.0f, 0.5f, 1.0f})
    for (float transmission : {0.0f, 1.0f, 2.0f})  // 2: transmission 1 into a volume
      for (float roughness : {0.0f, 0.05f, 0.3f, 1.0f})
        for (double cos_o : {1.0, 0.5, 0.1, 0.02}) {
          Pbr m;
          m.metallic = metallic, m.transmission = std::min(transmission, 1.0f), m.roughness = roughness;
          m.volume = transmission > 1 ? 1.0f : 0.0f;
          const auto s = sample(m, cos_o, 50000, seed++);
          const auto [mean, error] = mc_albedo(s);
          EXPECT_LE(mean, 1 + 4 * error + 1e-4) << "metallic " << metallic << ", transmission " << transmission
                                               << ", roughness " << roughness << ", cos " << cos_o;
          for (const ProbeOut& o : s) ASSERT_GE(o.weight.s[0], 0.0f);
        }
}

// f(wo, wi) = f(wi, wo): f cos_i / cos_i either way round, at random pairs on both sides.
TEST(PbrBsdf, IsReciprocalAndNonNegative) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  for (float roughness : {0.05f, 0.3f, 0.8f})
    for (float transmission : {0.0f, 0.6f}) {
      Pbr m;
      m.metallic = 0.3f, m.roughness = roughness, m.transmission = transmission, m.base = 0.8f;
      std::vector<cl_float4> forward, backward;
      for (int i = 0; i < 2000; ++i) {
        const cl_float4 a = direction(0.02 + 0.98 * u(rng), 2 * kPi * u(rng));
        const cl_float4 b = direction((u(rng) < 0.5 ? -1 : 1) * (0.02 + 0.98 * u(rng)), 2 * kPi * u(rng));
        forward.insert(forward.end(), {a, b});
        // The same pair seen from b's side: both mirrored when b lies below.
        const float flip = b.s[2] < 0 ? -1.0f : 1.0f;
        backward.insert(backward.end(), {cl_float4{{b.s[0], b.s[1], flip * b.s[2], 0}},
                                         cl_float4{{a.s[0], a.s[1], flip * a.s[2], 0}}});
      }
      const auto f = probe(m, forward), g = probe(m, backward);
      for (size_t i = 0; i < f.size(); ++i) {
        const double cos_a = std::fabs(forward[2 * i].s[2]), cos_b = std::fabs(forward[2 * i + 1].s[2]);
        const double fab = f[i].eval.s[0] / cos_b, fba = g[i].eval.s[0] / cos_a;
        ASSERT_GE(fab, 0);
        EXPECT_NEAR(fab, fba, 1e-4 * std::max(1.0, fab)) << "roughness " << roughness << " pair " << i;
      }
    }
}

// The density integrated over the sphere equals the share of samples the sampler keeps (a
// reflection drawn below the surface, a refraction above it or totally reflected is dropped), and a chi-square test of the directions against
// it passes: bins uniform in cos(theta) over [-1, 1] and in phi, each bin's expectation from the
// density evaluated at 4 x 4 points in it.
struct Chi2Result {
  double integral, kept, p_value;
};

Chi2Result chi2_of(const Pbr& m, double cos_o, unsigned seed) {
  constexpr int kTheta = 40, kPhi = 80, kSub = 4;
  constexpr size_t kSamples = 1000000;
  std::vector<cl_float4> grid;
  for (int t = 0; t < kTheta; ++t)
    for (int p = 0; p < kPhi; ++p)
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          grid.push_back(direction(cos_o, 0));
          grid.push_back(direction(-1 + 2 * (t + (a + 0.5) / kSub) / kTheta, 2 * kPi * (p + (b + 0.5) / kSub) / kPhi));
        }
  const auto eval = probe(m, grid);
  std::vector<double> expected(kTheta * kPhi, 0.0), observed(kTheta * kPhi, 0.0);
  const double cell = (2.0 / kTheta) * (2 * kPi / kPhi) / (kSub * kSub);  // d cos d phi per point
  double integral = 0;
  for (size_t i = 0; i < eval.size(); ++i) {
    expected[i / (kSub * kSub)] += eval[i].eval.s[3] * cell;
    integral += eval[i].eval.s[3] * cell;
  }
  const auto s = sample(m, cos_o, kSamples, seed);
  double kept = 0;
  for (const ProbeOut& o : s) {
    if (!(o.sampled.s[3] > 0)) continue;
    kept += 1;
    const double c = std::clamp<double>(o.sampled.s[2], -1, 1 - 1e-12);
    double phi = std::atan2(o.sampled.s[1], o.sampled.s[0]);
    if (phi < 0) phi += 2 * kPi;
    const int t = std::min(kTheta - 1, int((c + 1) / 2 * kTheta)), p = std::min(kPhi - 1, int(phi / (2 * kPi) * kPhi));
    observed[t * kPhi + p] += 1;
  }
  for (double& e : expected) e *= kSamples;
  return {integral, kept / kSamples, chi2_pooled_p_value(observed, expected)};
}

TEST(PbrBsdf, SampledDirectionsFollowTheirDensity) {
  struct Case {
    Pbr m;
    double cos_o;
  };
  const Case cases[] = {
      {{1, 0, 0.3f, 1.5f, 0}, 0.7},   {{0.8f, 0.5f, 0.6f, 1.5f, 0.5f}, 0.3}, {{1, 1, 0.25f, 1.5f, 0}, 0.9},
      {{0.5f, 0, 1.0f, 2.0f, 1}, 0.5}, {{0.9f, 0.2f, 0.4f, 1.3f, 0.8f}, 0.15},
      // Rough refraction into a volume and out of it (total internal reflection drops samples).
      {{0.9f, 0, 0.3f, 1.5f, 0.9f, 1}, 0.6}, {{0.9f, 0.1f, 0.5f, 1.5f, 1, 2}, 0.8},
      {{0.9f, 0, 0.4f, 1.33f, 1, 2}, 0.3},
  };
  const double alpha = 1 - std::pow(1 - 0.01, 1.0 / std::size(cases));  // Sidak over the cases
  unsigned seed = 11;
  for (const Case& c : cases) {
    const Chi2Result r = chi2_of(c.m, c.cos_o, seed++);
    // The density's integral is the kept share; the grid's error is under 1% at these roughnesses.
    EXPECT_NEAR(r.integral, r.kept, 0.01) << "roughness " << c.m.roughness << ", cos " << c.cos_o;
    EXPECT_LE(r.kept, 1.0);
    EXPECT_GT(r.p_value, alpha) << "roughness " << c.m.roughness << ", metallic " << c.m.metallic
                                << ", transmission " << c.m.transmission << ", cos " << c.cos_o;
  }
}

// The chi-square test can fail: the same directions against a density with the wrong roughness.
TEST(PbrBsdf, Chi2RejectsAWrongRoughness) {
  Pbr m{1, 1, 0.3f, 1.5f, 0};
  constexpr int kTheta = 40;
  const auto s = sample(m, 0.7, 200000, 5);
  m.roughness = 0.36f;
  std::vector<cl_float4> grid;
  // Compare the theta histogram with the density of the wrong material, integrated in phi.
  for (int t = 0; t < kTheta; ++t)
    for (int k = 0; k < 64; ++k)
      for (int p = 0; p < 64; ++p) {
        grid.push_back(direction(0.7, 0));
        grid.push_back(direction(-1 + 2 * (t + (k + 0.5) / 64) / kTheta, 2 * kPi * (p + 0.5) / 64));
      }
  const auto eval = probe(m, grid);
  std::vector<double> expected(kTheta, 0.0), observed(kTheta, 0.0);
  for (size_t i = 0; i < eval.size(); ++i) expected[i / 4096] += eval[i].eval.s[3] * (2.0 / kTheta / 64) * (2 * kPi / 64) * double(s.size());
  for (const ProbeOut& o : s)
    if (o.sampled.s[3] > 0) observed[std::min(kTheta - 1, int((o.sampled.s[2] + 1) / 2 * kTheta))] += 1;
  double statistic = 0;
  int cells = 0;
  for (int t = 0; t < kTheta; ++t)
    if (expected[t] >= 5) statistic += (observed[t] - expected[t]) * (observed[t] - expected[t]) / expected[t], ++cells;
  EXPECT_LT(chi2_survival(statistic, cells - 1), 1e-6);
}

}  // namespace
}  // namespace clpt::test
