// The host film: per-pixel sums of sample radiance and of its square, in double, added pass by
// pass from the device's float pass statistics. It yields the pixel mean and the variance of
// that mean, per channel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/types.h"

namespace clpt {

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return valid_.size(); }

  // Adds one pass over pixels [pixel_begin, pixel_begin + count) that took `samples` samples each.
  void add_pass(const std::vector<GpuPixelPass>& pass, size_t pixel_begin, uint32_t samples);

  // Mean radiance, RGB interleaved, row 0 at the top. Pixels without a valid sample are 0.
  std::vector<float> mean_rgb() const;
  // Variance of the pixel mean per channel: s^2 / n with s^2 the unbiased sample variance.
  // Pixels with fewer than two valid samples get 0.
  std::vector<float> variance_rgb() const;

  // Samples per pixel taken so far (the same for every pixel after whole passes).
  uint64_t samples_per_pixel() const { return samples_per_pixel_; }
  uint64_t total_samples() const { return total_samples_; }
  uint64_t total_segments() const { return total_segments_; }
  // Samples dropped because their radiance had a NaN or Inf channel.
  uint64_t dropped_samples() const { return dropped_samples_; }

 private:
  int width_, height_;
  std::vector<double> sum_;     // 3 per pixel
  std::vector<double> sum_sq_;  // 3 per pixel
  std::vector<double> valid_;   // valid samples per pixel
  uint64_t samples_per_pixel_ = 0;
  uint64_t total_samples_ = 0;
  uint64_t total_segments_ = 0;
  uint64_t dropped_samples_ = 0;
};

}  // namespace clpt
