// Adaptive sampling's host side (render/adaptive_sampling.h, render/pass_schedule.h): the rounds,
// the slot allocation and the passes, on films fed by a host stand-in for the devices. Each
// sample's value is a fixed function of (pixel, sample index), as the counter-based RNG makes a
// device's, so two simulated renders draw the same samples exactly when their films are equal.
// What the devices do with the slots (both execution forms, several devices, MPI ranks) is
// tested end to end in test_multi_device.cpp, test_forms.cpp and tests/mpi_cli.sh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "render/adaptive_sampling.h"
#include "render/film.h"
#include "render/pass_schedule.h"

namespace clpt::test {
namespace {

// A sample's radiance: pixel p's mean plus noise that is 40x larger in the image's left quarter.
float sample_value(uint32_t width, uint32_t pixel, uint32_t sample) {
  uint64_t h = (uint64_t(pixel) << 32 | sample) * 0x9E3779B97F4A7C15ull;
  h ^= h >> 29;
  h *= 0xBF58476D1CE4E5B9ull;
  h ^= h >> 32;
  const double u = double(h & 0xFFFFFF) / double(1 << 24) - 0.5;
  const bool noisy = pixel % width < width / 4;
  return float(0.5 + (noisy ? 4.0 : 0.1) * u);
}

GpuPixelPass pass_of(uint32_t width, uint32_t pixel, uint32_t first_sample, uint32_t samples) {
  GpuPixelPass p{};
  for (uint32_t s = 0; s < samples; ++s) {
    const float v = sample_value(width, pixel, first_sample + s);
    for (int c = 0; c < 3; ++c) {
      p.sum[c] += v;
      p.sum_sq[c] += v * v;
    }
  }
  p.valid_samples = float(samples);
  p.segments = samples;
  return p;
}

struct Simulated {
  Film film;
  std::vector<NextPass> passes;
  std::vector<std::set<uint32_t>> drawn;  // per pixel: the sample indices it drew
};

// A render of width x height by plan_next_pass and the pass loop's slot table, with the devices
// replaced by pass_of. `rate`: the samples per pixel per second the "devices" report.
Simulated simulate(uint32_t width, uint32_t height, PassRequest request, double rate) {
  Simulated sim{Film(int(width), int(height)), {}, std::vector<std::set<uint32_t>>(size_t(width) * height)};
  Film& film = sim.film;
  PassMeasurements measured;
  PassScheduleState state;
  AdaptiveSlotTable table;
  for (int guard = 0; guard < 100000; ++guard) {
    const NextPass next = plan_next_pass(film, request, measured, state);
    if (next.stop != StopReason::None) return sim;
    sim.passes.push_back(next);
    if (next.adaptive) {
      const std::vector<GpuSampleSlot> slots = table.pass_slots(film, next, request);
      EXPECT_EQ(slots.size(), next.slot_count);
      std::vector<GpuPixelPass> results;
      for (const GpuSampleSlot& s : slots) {
        results.push_back(pass_of(width, s.pixel, s.sample_begin, next.samples));
        for (uint32_t k = 0; k < next.samples; ++k)
          EXPECT_TRUE(sim.drawn[s.pixel].insert(s.sample_begin + k).second) << "pixel " << s.pixel << " drew a sample twice";
      }
      film.add_pass(results, 0, next.samples, &slots);
    } else {
      std::vector<GpuPixelPass> results;
      for (uint32_t p = 0; p < film.pixel_count(); ++p) {
        results.push_back(pass_of(width, p, next.sample_begin, next.samples));
        for (uint32_t k = 0; k < next.samples; ++k)
          EXPECT_TRUE(sim.drawn[p].insert(next.sample_begin + k).second) << "pixel " << p << " drew a sample twice";
      }
      film.add_pass(results, 0, next.samples, nullptr, next.half);
    }
    ++measured.passes;
    measured.samples_per_pixel_per_s = rate;
  }
  ADD_FAILURE() << "the render did not end";
  return sim;
}

PassRequest adaptive_request(uint64_t spp, uint32_t granularity = 1) {
  PassRequest r;
  r.target_spp = spp;
  r.granularity = granularity;
  r.adaptive = true;
  return r;
}

TEST(AdaptiveSampling, RoundsFollowTheLadderAndEndAtTheSampleCount) {
  const Simulated sim = simulate(32, 24, adaptive_request(100), 1e3);
  const Film& film = sim.film;
  EXPECT_EQ(film.samples_per_pixel(), 100u);
  EXPECT_EQ(film.half_samples_per_pixel(1), 50u);  // g ceil(S / 2g) with g = 1
  EXPECT_EQ(film.half_samples_per_pixel(0), 50u);
  EXPECT_EQ(film.half1_total_samples(), 50u * film.pixel_count());
  // Half 0 is uniform, a floor under every pixel; half 1 went where the noise is.
  double noisy = 0, quiet = 0;
  for (uint32_t p = 0; p < film.pixel_count(); ++p) {
    const double n0 = film.valid_counts()[p] - film.half1_valid_counts()[p];
    EXPECT_EQ(n0, 50.0);
    (p % 32 < 8 ? noisy : quiet) += film.half1_samples()[p];
  }
  EXPECT_GT(noisy / (8 * 24), 2.5 * quiet / (24 * 24));
  bool any_adaptive = false;
  for (const NextPass& p : sim.passes) any_adaptive |= p.adaptive;
  EXPECT_TRUE(any_adaptive);
}

TEST(AdaptiveSampling, PassesAndFilmDoNotDependOnTheMeasuredRate) {
  // The devices' speed sizes passes in the uniform mode; in adaptive mode the image alone does, so
  // a render on faster or more devices draws the same samples in the same passes.
  const Simulated slow = simulate(20, 10, adaptive_request(70), 50);
  const Simulated fast = simulate(20, 10, adaptive_request(70), 5e6);
  ASSERT_EQ(slow.passes.size(), fast.passes.size());
  for (size_t i = 0; i < slow.passes.size(); ++i) {
    EXPECT_EQ(slow.passes[i].samples, fast.passes[i].samples);
    EXPECT_EQ(slow.passes[i].slot_begin, fast.passes[i].slot_begin);
    EXPECT_EQ(slow.passes[i].slot_count, fast.passes[i].slot_count);
    EXPECT_EQ(slow.passes[i].sample_begin, fast.passes[i].sample_begin);
  }
  EXPECT_EQ(slow.film.sums(), fast.film.sums());
  EXPECT_EQ(slow.film.half1_samples(), fast.film.half1_samples());
}

TEST(AdaptiveSampling, GridSamplerSlotsHoldWholePeriods) {
  const Simulated sim = simulate(16, 8, adaptive_request(128, 16), 1e3);
  EXPECT_EQ(sim.film.samples_per_pixel(), 128u);
  for (uint32_t n : sim.film.half1_samples()) EXPECT_EQ(n % 16, 0u);
  for (const NextPass& p : sim.passes) EXPECT_EQ(p.samples % 16, 0u);
}

TEST(AdaptiveSampling, HalfOneSamplesContinueEachPixelsOwnSequence) {
  // Every pixel draws half 1's samples 2^31, 2^31 + 1, ... without a gap or a repeat (simulate
  // fails on a repeat): Sobol's points in order, the pixel's own count the next index.
  const Simulated sim = simulate(12, 9, adaptive_request(64), 1e3);
  for (uint32_t p = 0; p < sim.film.pixel_count(); ++p) {
    const uint32_t n1 = sim.film.half1_samples()[p];
    const auto first = sim.drawn[p].lower_bound(1u << CLPT_SAMPLE_STREAM_BIT);
    ASSERT_EQ(uint32_t(std::distance(first, sim.drawn[p].end())), n1);
    if (n1) {
      EXPECT_EQ(*sim.drawn[p].rbegin(), (1u << CLPT_SAMPLE_STREAM_BIT) + n1 - 1);
    }
  }
}

TEST(AdaptiveSampling, APixelsOwnSamplesDoNotChangeItsWeight) {
  // The unbiasedness argument (adaptive_sampling.h): a pixel's weight comes from its neighbours.
  // Pixel 45 (x 5, y 5, in the quiet part) alone is much noisier in film b.
  constexpr uint32_t kPixel = 45, kNeighbour = 44;
  Film a(8, 8), b(8, 8);
  std::vector<GpuPixelPass> pa, pb;
  for (uint32_t p = 0; p < 64; ++p) {
    pa.push_back(pass_of(8, p, 0, 16));
    pb.push_back(p == kPixel ? pass_of(8, p, 1000, 16) : pass_of(8, p, 0, 16));
  }
  for (int c = 0; c < 3; ++c) pb[kPixel].sum_sq[c] *= 50;
  a.add_pass(pa, 0, 16);
  b.add_pass(pb, 0, 16);
  const std::vector<double> wa = adaptive_weights(a), wb = adaptive_weights(b);
  EXPECT_EQ(wa[kPixel], wb[kPixel]);
  EXPECT_GT(wb[kNeighbour], 2 * wa[kNeighbour]);  // its neighbours weigh more
  // Its count moves only by the normalisation over the image (the 8 of 64 weights that grew).
  const std::vector<uint32_t> ca = adaptive_slot_counts(a, 640), cb = adaptive_slot_counts(b, 640);
  EXPECT_GT(cb[kNeighbour], ca[kNeighbour]);
  EXPECT_LE(cb[kPixel], ca[kPixel]);
  uint64_t total = 0;
  for (uint32_t n : cb) total += n;
  EXPECT_EQ(total, 640u);
}

TEST(AdaptiveSampling, OneFireflyCannotTakeTheRound) {
  Film film(16, 16);
  std::vector<GpuPixelPass> passes;
  for (uint32_t p = 0; p < 256; ++p) passes.push_back(pass_of(16, p, 0, 16));
  for (int c = 0; c < 3; ++c) passes[100].sum_sq[c] += 1e12f;
  film.add_pass(passes, 0, 16);
  const std::vector<uint32_t> counts = adaptive_slot_counts(film, 2560);  // 10 a pixel on average
  for (uint32_t n : counts) EXPECT_LE(n, uint32_t(std::ceil(kAdaptiveWeightCap * 10)) + 1);
}

TEST(AdaptiveSampling, TheTableSplitIntoPassesIsTheTableInOnePass) {
  Film film(6, 5);
  std::vector<GpuPixelPass> passes;
  for (uint32_t p = 0; p < 30; ++p) passes.push_back(pass_of(6, p, 0, 8));
  film.add_pass(passes, 0, 8);
  const std::vector<uint32_t> counts = adaptive_slot_counts(film, 90);
  const std::vector<GpuSampleSlot> whole = adaptive_pass_slots(film, counts, 1, 0, 90);
  Film split = film;
  std::vector<GpuSampleSlot> joined;
  for (uint64_t first = 0; first < 90; first += 37) {
    const std::vector<GpuSampleSlot> part = adaptive_pass_slots(split, counts, 1, first, std::min<uint64_t>(37, 90 - first));
    std::vector<GpuPixelPass> results;
    for (const GpuSampleSlot& s : part) results.push_back(pass_of(6, s.pixel, s.sample_begin, 1));
    split.add_pass(results, 0, 1, &part);
    joined.insert(joined.end(), part.begin(), part.end());
  }
  ASSERT_EQ(joined.size(), whole.size());
  for (size_t i = 0; i < whole.size(); ++i) {
    EXPECT_EQ(joined[i].pixel, whole[i].pixel);
    EXPECT_EQ(joined[i].sample_begin, whole[i].sample_begin);
  }
}

}  // namespace
}  // namespace clpt::test
