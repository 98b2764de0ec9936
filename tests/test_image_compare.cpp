// `clpt compare`'s tests (tools/image_compare.h): on synthetic noisy images whose distribution is
// known, and on small renders of the book's diffuse scene. The check: equal-distribution
// images pass, and a 2% brighter 64x64 region at 256 spp fails at the block level although the
// per-pixel acceptance stays >= 99.75%.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "render_test_util.h"
#include "tools/image_compare.h"

namespace clpt::test {
namespace {

constexpr int kSyntheticSize = 256;
// Noise "equivalent to 256 spp": per-sample standard deviation equal to the pixel mean (about
// what diffuse interreflection gives), so the pixel mean's is mean / sqrt(256).
constexpr double kSyntheticSpp = 256;

// A smooth coloured gradient: the true pixel mean of the synthetic images, never 0.
double true_mean(int x, int y, int c) {
  return 0.1 + 0.5 * double(x) / kSyntheticSize + 0.3 * double(y) / kSyntheticSize + 0.1 * c;
}

// One synthetic render: true_mean (times `gain` inside [x0,x1) x [y0,y1)) plus normal noise,
// with the exact variance of the mean in the variance channels.
struct Gain {
  double factor = 1.0;
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
};

MeanVarianceImage synthetic_render(uint32_t seed, const Gain& gain = {}) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  MeanVarianceImage img;
  img.width = img.height = kSyntheticSize;
  for (int y = 0; y < kSyntheticSize; ++y)
    for (int x = 0; x < kSyntheticSize; ++x)
      for (int c = 0; c < 3; ++c) {
        const bool inside = x >= gain.x0 && x < gain.x1 && y >= gain.y0 && y < gain.y1;
        const double m = true_mean(x, y, c) * (inside ? gain.factor : 1.0);
        const double sigma = true_mean(x, y, c) / std::sqrt(kSyntheticSpp);
        img.mean.push_back(float(m + sigma * normal(rng)));
        img.variance.push_back(float(sigma * sigma));
      }
  return img;
}

bool any_block_scale_fails(const CompareResult& r) {
  for (const BlockScaleResult& s : r.scales)
    if (!s.pass) return true;
  return false;
}

TEST(CompareStatistics, SidakAndCriticalZ) {
  EXPECT_NEAR(critical_z(0.05), 1.959964, 1e-5);
  EXPECT_NEAR(critical_z(0.01), 2.575829, 1e-5);
  EXPECT_NEAR(sidak_alpha(0.01, 3), 1 - std::pow(0.99, 1.0 / 3), 1e-12);
  EXPECT_NEAR(sidak_alpha(0.01, 1e6) * 1e6, 0.01005, 1e-4);  // tiny results keep their precision
  EXPECT_NEAR(two_sided_p_value(-1.959964), 0.05, 1e-6);
}

TEST(CompareSynthetic, EqualDistributionsPass) {
  const CompareResult r = compare_renders(synthetic_render(1), synthetic_render(2), CompareOptions{});
  EXPECT_TRUE(r.pass) << format_compare_report(r, {"a", 256}, {"b", 256});
  EXPECT_GE(r.accept_fraction, 0.9975);
  ASSERT_EQ(r.scales.size(), 3u);
  EXPECT_EQ(r.scales[0].block_count, 16 * 16);
  EXPECT_LT(r.equal_fraction, 0.01);  // independent noise: almost no pixel is equal
}

TEST(CompareSynthetic, TwoPercentBrighterRegionFailsAtBlockLevelOnly) {
  const Gain gain{1.02, 96, 64, 160, 128};  // 64x64, not aligned with the 64-pixel blocks
  const CompareResult r = compare_renders(synthetic_render(1, gain), synthetic_render(2), CompareOptions{});
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(any_block_scale_fails(r)) << format_compare_report(r, {"a", 256}, {"b", 256});
  EXPECT_GE(r.accept_fraction, 0.9975) << "no single pixel should show a 2% shift at 256 spp";
  // The worst 32x32 block overlaps the brighter region, and A is brighter there.
  const WorstBlock& w = r.scales[1].worst;
  EXPECT_GT(w.x + w.width, 96);
  EXPECT_LT(w.x, 160);
  EXPECT_GT(w.y + w.height, 64);
  EXPECT_LT(w.y, 128);
  EXPECT_GT(w.z, 0);
}

TEST(CompareSynthetic, GloballyBrighterImageFails) {
  const Gain everywhere{1.03, 0, 0, kSyntheticSize, kSyntheticSize};
  const CompareResult r = compare_renders(synthetic_render(1, everywhere), synthetic_render(2), CompareOptions{});
  EXPECT_FALSE(r.pass);
  EXPECT_FALSE(r.image_mean.pass);
  for (int c = 0; c < 3; ++c) EXPECT_GT(r.image_mean.z[c], r.image_mean.z_critical);
}

TEST(CompareSynthetic, IdenticalImagesPassSameSeed) {
  const MeanVarianceImage a = synthetic_render(7);
  CompareOptions options;
  options.same_seed = true;
  const CompareResult r = compare_renders(a, a, options);
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.equal_fraction, 1.0);
  EXPECT_EQ(r.accept_fraction, 1.0);
}

TEST(CompareSynthetic, PerturbedPixelsFailSameSeed) {
  const MeanVarianceImage a = synthetic_render(7);
  MeanVarianceImage b = a;
  // Every 20th pixel (5%) 1% brighter in one channel: far outside a 1e-4 tolerance.
  for (size_t p = 0; p < b.mean.size() / 3; p += 20) b.mean[p * 3 + p % 3] *= 1.01f;
  CompareOptions options;
  options.same_seed = true;
  const CompareResult r = compare_renders(a, b, options);
  EXPECT_FALSE(r.pass);
  EXPECT_NEAR(r.equal_fraction, 0.95, 0.001);
  EXPECT_TRUE(r.statistical_pass) << "a 1% change at 256 spp noise is statistically invisible";
}

// Without variance (e.g. a black background, or the light seen directly) values must match
// exactly, within 1e-6 relative.
TEST(CompareSynthetic, ZeroVariancePixelsMustAgree) {
  MeanVarianceImage a;
  a.width = a.height = 8;
  a.mean.assign(8 * 8 * 3, 0.25f);
  a.variance.assign(8 * 8 * 3, 0.0f);
  MeanVarianceImage b = a;
  EXPECT_TRUE(compare_renders(a, b, CompareOptions{}).pass);
  b.mean[0] = 0.2500001f;
  EXPECT_TRUE(compare_renders(a, b, CompareOptions{}).pass);
  b.mean[0] = 0.26f;
  const CompareResult r = compare_renders(a, b, CompareOptions{});
  EXPECT_EQ(r.accepted_pixels, r.pixel_count - 1);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(std::isinf(r.scales[0].worst.z));
  const std::string json = compare_report_json(r, {"a \"quoted\"", std::nullopt}, {"b", 1});
  EXPECT_EQ(json.find("inf"), std::string::npos) << "JSON has no infinity: " << json;
  EXPECT_NE(json.find("\"a \\\"quoted\\\"\""), std::string::npos) << json;
}

TEST(CompareSynthetic, NaNNeverAccepts) {
  const MeanVarianceImage a = synthetic_render(3);
  MeanVarianceImage b = synthetic_render(4);
  const CompareResult clean = compare_renders(a, b, CompareOptions{});
  b.mean[5] = std::numeric_limits<float>::quiet_NaN();  // pixel 1, channel B
  const CompareResult r = compare_renders(a, b, CompareOptions{});
  EXPECT_EQ(r.accepted_pixels, clean.accepted_pixels - 1);
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(std::isnan(r.scales[0].worst.z));
}

TEST(CompareSynthetic, DiffRampColours) {
  const std::vector<unsigned char> rgb = z_to_colour_ramp(
      {-8.0f, -2.0f, 0.0f, 4.0f, std::numeric_limits<float>::quiet_NaN()});
  const std::vector<unsigned char> expected = {0, 0, 255, 128, 128, 255, 255, 255, 255, 255, 0, 0, 0, 0, 0};
  EXPECT_EQ(rgb, expected);
}

TEST(CompareSynthetic, MismatchedSizesAreRejected) {
  MeanVarianceImage small = synthetic_render(1);
  small.height -= 1;
  small.mean.resize(small.mean.size() - 3 * kSyntheticSize);
  small.variance.resize(small.variance.size() - 3 * kSyntheticSize);
  EXPECT_THROW(compare_renders(small, synthetic_render(2), {}), std::invalid_argument);
}

// Real renders: the diffuse scene at 64x48, 256 spp (jitter). Each is rendered on first use and
// kept, since ctest runs every test in its own process and should render only what it needs.
class CompareRenders : public ::testing::Test {
 protected:
  static constexpr int kWidth = 64, kHeight = 48;

  static MeanVarianceImage render(uint64_t seed) {
    const TestRender r = render_for_test(load_book_scene("diffuse"), kWidth, kHeight, 256, seed);
    return r.film.mean_variance();
  }
  static const MeanVarianceImage& seed1() {
    static const MeanVarianceImage image = render(1);
    return image;
  }
  static const MeanVarianceImage& seed2() {
    static const MeanVarianceImage image = render(2);
    return image;
  }
  static const MeanVarianceImage& seed1_again() {
    static const MeanVarianceImage image = render(1);
    return image;
  }
};

TEST_F(CompareRenders, DifferentSeedsPass) {
  const CompareResult r = compare_renders(seed1(), seed2(), CompareOptions{});
  EXPECT_TRUE(r.pass) << format_compare_report(r, {"seed 1", 256}, {"seed 2", 256});
}

TEST_F(CompareRenders, SameSeedTwiceIsIdentical) {
  CompareOptions options;
  options.same_seed = true;
  const CompareResult r = compare_renders(seed1(), seed1_again(), options);
  EXPECT_TRUE(r.pass);
  EXPECT_EQ(r.equal_fraction, 1.0);
}

// A gain on the 32x32 block at the top left. Not 2%: at 256 spp this scene's pixel noise is so
// high (no next-event estimation) that a 2% gain moves that block's mean by only z = 2.5 to 2.8
// (by channel), below the 3.34 at which the 32-pixel scale rejects, so no test at alpha 0.01 could
// be relied on to see it; 5% moves it by z = 6 to 7. The synthetic test above covers 2%.
TEST_F(CompareRenders, FivePercentGainOnRegionFailsAtBlockLevel) {
  MeanVarianceImage brighter = seed1();
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 32; ++x)
      for (int c = 0; c < 3; ++c) brighter.mean[(size_t(y) * kWidth + x) * 3 + c] *= 1.05f;
  const CompareResult r = compare_renders(brighter, seed2(), CompareOptions{});
  EXPECT_FALSE(r.pass);
  EXPECT_TRUE(any_block_scale_fails(r)) << format_compare_report(r, {"seed 1 +5%", 256}, {"seed 2", 256});
  // (The pixel test may fail too: pixels that see only the light have zero variance, and a gain
  // makes them certainly different.)
}

}  // namespace
}  // namespace clpt::test
