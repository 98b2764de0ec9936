// The host film: double accumulation across passes, variance of the mean, dropped samples.
#include <gtest/gtest.h>

#include "render/film.h"
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

}  // namespace
}  // namespace clpt
