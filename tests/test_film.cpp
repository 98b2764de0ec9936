// The host film: double accumulation across passes, variance of the mean, dropped samples; its
// half-films, the error estimate made from them, and the schedule of passes that uses it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>

#include "render/error_estimate.h"
#include "render/film.h"
#include "render/film_raw.h"
#include "util/error.h"
#include "render/pass_schedule.h"
#include "render/render_session.h"

namespace clpt {
namespace {

GpuPixelPass pass_of(const std::vector<float>& values) {
  GpuPixelPass p{};
  for (float v : values) {
    for (int c = 0; c < 3; ++c) {
      p.sum[c] += v;
      p.sum_sq[c] += v * v;
    }
    p.valid_samples += 1;
  }
  return p;
}

TEST(Film, MeanAndVarianceOfTheMeanAcrossPasses) {
  Film film(1, 1);
  film.add_pass({pass_of({1, 2})}, 0, 2);
  film.add_pass({pass_of({3, 4, 5})}, 0, 3);
  EXPECT_EQ(film.samples_per_pixel(), 5u);
  EXPECT_FLOAT_EQ(film.mean_rgb()[0], 3.0f);
  // Sample variance of 1..5 is 2.5; of the mean, 2.5 / 5.
  EXPECT_FLOAT_EQ(film.variance_rgb()[1], 0.5f);
}

TEST(Film, DroppedSamplesAreCountedAndExcluded) {
  Film film(1, 1);
  GpuPixelPass p = pass_of({2, 2});
  film.add_pass({p}, 0, 3);  // three samples taken, two valid
  EXPECT_EQ(film.dropped_samples(), 1u);
  EXPECT_FLOAT_EQ(film.mean_rgb()[2], 2.0f);
}

TEST(PassSizing, FirstPassIsOnePeriodThenAimsAtTheTarget) {
  EXPECT_EQ(next_pass_samples(0, 64, 0, 0.5, 16), 16u);
  EXPECT_EQ(next_pass_samples(16, 64, 1000, 0.5, 16), 48u);  // capped by what is left
  EXPECT_EQ(next_pass_samples(0, 0, 100, 0.5, 1), 50u);       // time-bounded: 0.5 s worth
  EXPECT_EQ(next_pass_samples(0, 0, 1e9, 0.5, 1), kMaxSamplesPerPass);
}

TEST(FilmHalves, EachPassGoesWholeToTheSmallerHalf) {
  Film film(2, 1);
  EXPECT_EQ(film.next_half(), 0);
  film.add_pass({pass_of({1}), pass_of({1})}, 0, 1);  // half 0: 1
  EXPECT_EQ(film.next_half(), 1);
  film.add_pass({pass_of({3, 3})}, 0, 2);  // half 1, in two launches
  EXPECT_EQ(film.next_half(), 1);         // the pass is not complete yet: still half 1
  film.add_pass({pass_of({5, 5})}, 1, 2);
  EXPECT_EQ(film.half_samples_per_pixel(0), 1u);
  EXPECT_EQ(film.half_samples_per_pixel(1), 2u);
  EXPECT_EQ(film.next_half(), 0);
  EXPECT_DOUBLE_EQ(film.half1_sums()[0], 6.0);
  EXPECT_DOUBLE_EQ(film.half1_sums()[3], 10.0);
  EXPECT_DOUBLE_EQ(film.half1_valid_counts()[1], 2.0);
}

TEST(ErrorEstimate, EqualHalvesGiveAQuarterOfTheirSquaredDifference) {
  Film film(1, 1);
  EXPECT_FALSE(estimate_error(film).valid);
  film.add_pass({pass_of({1, 1})}, 0, 2);
  EXPECT_FALSE(estimate_error(film).valid);  // one half only
  film.add_pass({pass_of({3, 3})}, 0, 2);
  const ErrorEstimate e = estimate_error(film);
  ASSERT_TRUE(e.valid);
  EXPECT_DOUBLE_EQ(e.mse, 1.0);  // (1 - 3)^2 / 4
  EXPECT_DOUBLE_EQ(e.image_mean, 2.0);
  EXPECT_DOUBLE_EQ(e.relative_rmse, 0.5);
  EXPECT_DOUBLE_EQ(e.relative_rmse_upper, 0.5);  // every term equal: no spread
}

// A stratified toy: each pass of n samples integrates f(u) = u over n equal strata, one uniform
// point in each. The mean of one pass has variance 1/(12 n^3), the film of two passes 1/(24 n^3);
// the per-pixel sample variance s^2/(2n) says about 1/(24 n), n^2 times too much. The half-film
// estimate must find 1/(24 n^3): it is a mean over 3 x 4000 terms, each a scaled chi-square with
// one degree of freedom (relative standard deviation sqrt(2)), so within 5 standard errors of it.
TEST(ErrorEstimate, IsUnbiasedForAStratifiedSampler) {
  constexpr int kPixels = 4000, kStrata = 8;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  Film film(kPixels, 1);
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<GpuPixelPass> passes;
    for (int p = 0; p < kPixels; ++p) {
      std::vector<float> values;
      for (int i = 0; i < kStrata; ++i) values.push_back((float(i) + uniform(rng)) / kStrata);
      passes.push_back(pass_of(values));
    }
    film.add_pass(passes, 0, kStrata);
  }
  const ErrorEstimate e = estimate_error(film);
  const double expected = 1.0 / (24.0 * kStrata * kStrata * kStrata);
  const double standard_error = expected * std::sqrt(2.0 / (3.0 * kPixels));
  EXPECT_NEAR(e.mse, expected, 5 * standard_error);
  EXPECT_NEAR(e.image_mean, 0.5, 1e-3);
  const std::vector<float> variance = film.variance_rgb();
  double variance_mean = 0;
  for (float v : variance) variance_mean += v / double(variance.size());
  EXPECT_GT(variance_mean, 20 * expected);  // what the per-pixel variance would have claimed
}

TEST(PassSchedule, CheckLadderStartsAt16AndGrowsByAnEighth) {
  EXPECT_EQ(check_ladder_at_or_above(0, 1), 16u);
  EXPECT_EQ(check_ladder_at_or_above(16, 1), 16u);
  EXPECT_EQ(check_ladder_at_or_above(17, 1), 18u);
  EXPECT_EQ(check_ladder_at_or_above(0, 16), 32u);
  EXPECT_EQ(check_ladder_at_or_above(33, 16), 64u);
  for (uint64_t spp : {100u, 1000u, 100000u}) {
    const uint64_t point = check_ladder_at_or_above(spp, 1);
    EXPECT_GE(point, spp);
    EXPECT_LE(point, spp + spp / 8 + 2);
    EXPECT_EQ(point % 2, 0u);
  }
}

// A 1x1 film whose two halves hold `a` and `b` samples of value 1 and 3.
Film film_with_halves(uint32_t a, uint32_t b) {
  Film film(1, 1);
  film.add_pass({pass_of(std::vector<float>(a, 1.0f))}, 0, a);
  if (b) film.add_pass({pass_of(std::vector<float>(b, 3.0f))}, 0, b);
  return film;
}

TEST(PassSchedule, TargetErrorStopsOnlyAtACheckPointWithEqualHalves) {
  PassRequest request;
  request.target_error = 0.6;  // the films above estimate 0.5
  PassMeasurements measured;
  measured.passes = 1;
  {
    PassScheduleState state;
    const NextPass first = plan_next_pass(Film(1, 1), request, measured, state);
    EXPECT_EQ(first.stop, StopReason::None);
    EXPECT_EQ(first.samples, 1u);  // no rate yet: one sampler period
    EXPECT_EQ(state.next_check_spp, 16u);
  }
  {
    PassScheduleState state;  // 4 + 4 samples: below the first check point, go on
    const NextPass next = plan_next_pass(film_with_halves(4, 4), request, measured, state);
    EXPECT_EQ(next.stop, StopReason::None);
    EXPECT_EQ(next.half, 0);
    measured.samples_per_pixel_per_s = 1e6;
    EXPECT_EQ(plan_next_pass(film_with_halves(4, 4), request, measured, state).samples, 4u);  // to 8 + 8
  }
  {
    PassScheduleState state;  // 8 + 4: half 1 catches up first
    const NextPass next = plan_next_pass(film_with_halves(8, 4), request, measured, state);
    EXPECT_EQ(next.stop, StopReason::None);
    EXPECT_EQ(next.half, 1);
    EXPECT_EQ(next.samples, 4u);
  }
  {
    PassScheduleState state;  // 8 + 8 at the check point 16, estimate 0.5 <= 0.6: stop
    EXPECT_EQ(plan_next_pass(film_with_halves(8, 8), request, measured, state).stop, StopReason::TargetError);
  }
  {
    request.target_error = 0.25;  // needs 4x the samples: the next check point jumps towards 64
    PassScheduleState state;
    const NextPass next = plan_next_pass(film_with_halves(8, 8), request, measured, state);
    EXPECT_EQ(next.stop, StopReason::None);
    EXPECT_EQ(next.predicted_spp, 64u);
    EXPECT_EQ(state.next_check_spp, check_ladder_at_or_above(24, 1));  // the jump: at most 1.5 x 16
  }
}

// Whatever the measured rates (so the pass sizes), a render of S samples ends with the same halves
// and draws the same sample indices: half 0 from 0, half 1 from 2^31.
TEST(PassSchedule, HalvesAtTheEndDependOnTheSampleCountAlone) {
  std::mt19937 rng(3);
  for (bool power_of_two_halves : {false, true})
  for (uint32_t granularity : {1u, 16u})
    for (uint64_t spp : {6u, 16u, 48u, 77u, 1000u}) {
      if (spp % granularity) continue;
      for (int trial = 0; trial < 20; ++trial) {
        PassRequest request;
        request.target_spp = spp;
        request.granularity = granularity;
        request.power_of_two_halves = power_of_two_halves;
        PassMeasurements measured;
        PassScheduleState state;
        Film film(1, 1);
        for (;;) {
          measured.samples_per_pixel_per_s = std::uniform_real_distribution<double>(0, 400)(rng);
          const NextPass next = plan_next_pass(film, request, measured, state);
          if (next.stop != StopReason::None) break;
          EXPECT_EQ(next.sample_begin, (uint64_t(next.half) << 31) + film.half_samples_per_pixel(next.half));
          film.add_pass({pass_of(std::vector<float>(next.samples, 1.0f))}, 0, next.samples, nullptr, next.half);
          ++measured.passes;
        }
        const uint64_t half0 = half0_end(spp, granularity, power_of_two_halves);
        EXPECT_EQ(film.samples_per_pixel(), spp);
        EXPECT_EQ(film.half_samples_per_pixel(0), half0) << spp << " spp, granularity " << granularity;
        EXPECT_EQ(film.half_samples_per_pixel(1), spp - half0);
      }
    }
}

TEST(PassSchedule, HalfZeroEndsAtItsShareOrThePowerOfTwoAboveIt) {
  // Equal shares, rounded up to the granularity.
  EXPECT_EQ(half0_end(6, 1, false), 3u);
  EXPECT_EQ(half0_end(7, 1, false), 4u);
  EXPECT_EQ(half0_end(1, 1, false), 1u);
  EXPECT_EQ(half0_end(48, 16, false), 32u);
  // Sobol nets: the smallest power of two at or above the share, at most the whole render.
  const std::pair<uint64_t, uint64_t> pow2[] = {{1, 1}, {2, 1}, {3, 2}, {5, 4}, {6, 4}, {7, 4}, {8, 4},
                                                {9, 8}, {12, 8}, {17, 16}, {1000, 512}};
  for (const auto& [spp, half0] : pow2) EXPECT_EQ(half0_end(spp, 1, true), half0) << spp << " spp";
}

TEST(PassSchedule, SampleCountAndTimeLimitStopTheRender) {
  PassRequest request;
  request.target_spp = 16;
  PassMeasurements measured;
  PassScheduleState state;
  EXPECT_EQ(plan_next_pass(film_with_halves(8, 8), request, measured, state).stop, StopReason::SampleCount);
  request.target_spp = 0;
  request.time_limit_s = 1;
  measured.passes = 1;
  measured.elapsed_s = 1.5;
  EXPECT_EQ(plan_next_pass(film_with_halves(8, 8), request, measured, state).stop, StopReason::TimeLimit);
}

// Raw films (render/film_raw.h): what write_film_pfm writes, read_film_pfm reads back bit for
// bit, rows in order; a file that lies about its size or is cut short is refused, naming it.
TEST(RawFilm, PfmRoundTripAndRefusals) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "clpt_test_raw_film";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  MeanVarianceImage image;
  image.width = 3;
  image.height = 2;
  for (int i = 0; i < 18; ++i) {
    image.mean.push_back(0.25f * float(i) + 1e-7f);
    image.variance.push_back(1e-3f * float(i * i));
  }
  const std::string path = (dir / "film.pfm").string();
  write_film_pfm(path, image);
  EXPECT_EQ(variance_pfm_path(path), (dir / "film.var.pfm").string());
  const MeanVarianceImage back = read_film_pfm(path);
  EXPECT_EQ(back.width, 3);
  EXPECT_EQ(back.height, 2);
  EXPECT_EQ(back.mean, image.mean);
  EXPECT_EQ(back.variance, image.variance);

  const auto expect_refused = [&](const std::string& bytes, const std::string& needle) {
    const std::string bad = (dir / "bad.pfm").string();
    std::ofstream(bad, std::ios::binary) << bytes;
    std::filesystem::copy_file(dir / "film.var.pfm", dir / "bad.var.pfm",
                               std::filesystem::copy_options::overwrite_existing);
    try {
      read_film_pfm(bad);
      ADD_FAILURE() << "accepted: " << needle;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  expect_refused("Pf\n3 2\n-1.0\n", "does not start with 'PF'");
  expect_refused("PF\n3 2\n-1.0\n" + std::string(10, 'x'), "must hold 72 bytes");
  expect_refused("PF\n100000 2\n-1.0\n", "is not in 1..16384");
  expect_refused("PF\n3 2\n0\n", "is not a non-zero number");
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace clpt
