// The sampler's draws on the device (kernels/sampler.cl): the Sobol sampler's power-of-two
// prefixes are stratified in every elementary-interval shape, its points depend on the pixel, the
// dimension and the seed, and on nothing about the launch; the jitter sampler still draws exactly
// the Philox numbers it drew before the Sobol sampler existed.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <utility>

#include "device_test_util.h"
#include "kernels/types.h"

namespace clpt::test {
namespace {

// Samples sample_begin .. sample_begin + count - 1 of (pixel, dimension) from `sampler`.
std::vector<cl_float4> draw(cl_uint sampler, cl_uint pixel, cl_uint dimension, cl_uint sample_begin, size_t count,
                            cl_uint k0 = 7, cl_uint k1 = 0) {
  return run_probe<cl_float4>("probe_sampler", count, k0, k1, sampler, pixel, dimension, sample_begin);
}

// Number of distinct cells [i/2^a, (i+1)/2^a) x [j/2^b, (j+1)/2^b) that the first n points of the
// pair (components cx, cy) fall in. The draws are multiples of 2^-24, so the products are exact.
size_t occupied_cells(const std::vector<cl_float4>& u, size_t n, int cx, int cy, int a, int b) {
  std::set<std::pair<long, long>> cells;
  for (size_t i = 0; i < n; ++i)
    cells.emplace(long(std::floor(u[i].s[cx] * float(1 << a))), long(std::floor(u[i].s[cy] * float(1 << b))));
  return cells.size();
}

// Owen scrambling keeps the (0,2)-sequence's nets: every first 2^k samples of a pair put exactly
// one point in each of the 2^k elementary intervals of every shape 2^-a x 2^-(k-a). A shuffle or
// scramble that broke the nesting puts two points in some interval and fails here.
TEST(SobolSampler, PowerOfTwoPrefixesAreStratifiedInEveryShape) {
  constexpr int kMaxLog = 10;
  constexpr cl_uint kLightAtBounce2 = 0x40000002u;  // CLPT_DIM_LIGHT + 2 (kernels/light.cl)
  for (cl_uint pixel : {0u, 12345u})
    for (cl_uint dimension : {0u, 3u, kLightAtBounce2}) {
      const auto u = draw(CLPT_SAMPLER_SOBOL, pixel, dimension, 0, size_t(1) << kMaxLog);
      for (int pair = 0; pair < 2; ++pair)
        for (int k = 0; k <= kMaxLog; ++k)
          for (int a = 0; a <= k; ++a)
            ASSERT_EQ(occupied_cells(u, size_t(1) << k, 2 * pair, 2 * pair + 1, a, k - a), size_t(1) << k)
                << "pixel " << pixel << " dimension " << dimension << " pair " << pair << ": 2^" << k
                << " samples in cells 2^-" << a << " x 2^-" << k - a;
    }
}

// An aligned block of 2^k later samples is a net too (the sequence property, not only prefixes).
TEST(SobolSampler, AlignedBlocksAreStratified) {
  const auto u = draw(CLPT_SAMPLER_SOBOL, 99, 1, 256, 256);
  for (int a = 0; a <= 8; ++a) EXPECT_EQ(occupied_cells(u, 256, 0, 1, a, 8 - a), 256u) << "shape 2^-" << a;
}

// Points for another pixel, dimension, pair or seed are other points: equal ones would correlate
// pixels or bounces (the image would show structure, or the dimensions would not be independent).
TEST(SobolSampler, PixelsDimensionsPairsAndSeedsDiffer) {
  constexpr size_t n = 64;
  const auto base = draw(CLPT_SAMPLER_SOBOL, 5, 1, 0, n);
  const auto other_pixel = draw(CLPT_SAMPLER_SOBOL, 6, 1, 0, n);
  const auto other_dimension = draw(CLPT_SAMPLER_SOBOL, 5, 2, 0, n);
  const auto other_seed = draw(CLPT_SAMPLER_SOBOL, 5, 1, 0, n, 8, 0);
  size_t same_pixel = 0, same_dimension = 0, same_seed = 0, same_pair = 0;
  for (size_t i = 0; i < n; ++i) {
    same_pixel += base[i].s[0] == other_pixel[i].s[0];
    same_dimension += base[i].s[0] == other_dimension[i].s[0];
    same_seed += base[i].s[0] == other_seed[i].s[0];
    same_pair += base[i].s[0] == base[i].s[2];
  }
  // Independent 24-bit values coincide with probability 2^-24 each.
  EXPECT_EQ(same_pixel, 0u);
  EXPECT_EQ(same_dimension, 0u);
  EXPECT_EQ(same_seed, 0u);
  EXPECT_EQ(same_pair, 0u);
}

// Counter-addressed: sample 613 drawn alone equals sample 613 drawn among 1000, whatever the
// launch's first sample or size.
TEST(SobolSampler, IndependentOfLaunch) {
  const auto all = draw(CLPT_SAMPLER_SOBOL, 42, 4, 0, 1000);
  const auto one = draw(CLPT_SAMPLER_SOBOL, 42, 4, 613, 1);
  for (int c = 0; c < 4; ++c) EXPECT_EQ(all[613].s[c], one[0].s[c]);
}

// Every draw lies in [0, 1).
TEST(SobolSampler, DrawsAreInTheUnitInterval) {
  const auto u = draw(CLPT_SAMPLER_SOBOL, 3, 0, 0, 4096);
  for (const cl_float4& v : u)
    for (int c = 0; c < 4; ++c) {
      ASSERT_GE(v.s[c], 0.0f);
      ASSERT_LT(v.s[c], 1.0f);
    }
}

// The camera's sub-pixel positions for samples sample_begin .. sample_begin + count - 1 of `pixel`.
std::vector<cl_float2> subpixels(cl_uint sampler, cl_uint pixel, cl_uint sample_begin, size_t count) {
  return run_probe<cl_float2>("probe_subpixel", count, cl_uint(7), cl_uint(0), sampler, pixel, sample_begin);
}

// The grid sampler's 16 positions (the centres of 4x4 strata), as indices 0..15, or -1 for any
// other position.
int grid_position(const cl_float2& p) {
  const float cx = p.s[0] * 4.0f - 0.5f, cy = p.s[1] * 4.0f - 0.5f;
  const int ix = int(std::lround(cx)), iy = int(std::lround(cy));
  return cx == float(ix) && cy == float(iy) && ix >= 0 && ix < 4 && iy >= 0 && iy < 4 ? ix + 4 * iy : -1;
}

// sobol-grid puts every camera sample on one of the grid's 16 positions, and every aligned block
// of 16 samples on each of them once: it converges to the grid's image, and 16 samples of it are
// the grid's own. Counts below 16 are spread (any 4 aligned samples in 4 different rows and
// columns of the 4x4 grid). Plain Sobol positions are not on the grid.
TEST(SobolGridSampler, VisitsEachGridPositionOncePerSixteenSamples) {
  for (cl_uint pixel : {0u, 777u, 307199u}) {
    const auto p = subpixels(CLPT_SAMPLER_SOBOL_GRID, pixel, 0, 64);
    for (size_t block = 0; block < 4; ++block) {
      std::set<int> seen;
      for (size_t i = 16 * block; i < 16 * block + 16; ++i) {
        const int g = grid_position(p[i]);
        ASSERT_GE(g, 0) << "pixel " << pixel << " sample " << i << " at (" << p[i].s[0] << ", " << p[i].s[1] << ")";
        seen.insert(g);
      }
      EXPECT_EQ(seen.size(), 16u) << "pixel " << pixel << " samples " << 16 * block << "..";
    }
    for (size_t quad = 0; quad < 16; ++quad) {
      std::set<int> rows, columns;
      for (size_t i = 4 * quad; i < 4 * quad + 4; ++i) {
        columns.insert(grid_position(p[i]) % 4);
        rows.insert(grid_position(p[i]) / 4);
      }
      EXPECT_EQ(rows.size() + columns.size(), 8u) << "pixel " << pixel << " samples " << 4 * quad << "..";
    }
    // The same Sobol point, not snapped: off the grid (a point of the 2^-24 lattice lands on a
    // centre with probability 2^-22 per coordinate).
    const auto plain = subpixels(CLPT_SAMPLER_SOBOL, pixel, 0, 16);
    for (size_t i = 0; i < plain.size(); ++i) {
      EXPECT_EQ(grid_position(plain[i]), -1) << "pixel " << pixel << " sample " << i;
      EXPECT_EQ(int(plain[i].s[0] * 4) + 4 * int(plain[i].s[1] * 4), grid_position(p[i])) << "the stratum of its own point";
    }
  }
}

// The jitter and grid samplers draw Philox4x32-10 at counter (pixel, sample, dimension, 0), top 24
// bits of each word: the numbers every jitter image was made with before the Sobol sampler.
TEST(JitterSampler, DrawsThePhiloxNumbers) {
  std::vector<cl_uint4> counters;
  for (cl_uint i = 0; i < 16; ++i) counters.push_back(cl_uint4{{77u, i, 5u, 0u}});
  const auto bits = run_philox(counters, 7, 0);
  for (cl_uint sampler : {CLPT_SAMPLER_JITTER, CLPT_SAMPLER_GRID}) {
    const auto u = draw(sampler, 77, 5, 0, counters.size());
    for (size_t i = 0; i < counters.size(); ++i)
      for (int c = 0; c < 4; ++c) EXPECT_EQ(u[i].s[c], float(bits[i].s[c] >> 8) * 0x1.0p-24f) << i << " " << c;
  }
}

}  // namespace
}  // namespace clpt::test
