// The host film: per-pixel sums of sample radiance and of its square, in double, added pass by
// pass from the device's float pass statistics. It yields the pixel mean and the variance of
// that mean, per channel.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/types.h"

namespace clpt {

// A render as the statistics see it: per pixel the mean and the variance of the mean, RGB
// interleaved (3 floats a pixel), row 0 at the top.
struct MeanVarianceImage {
  int width = 0;
  int height = 0;
  std::vector<float> mean;
  std::vector<float> variance;
};

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return valid_.size(); }

  // Adds one launch's statistics for pixels [pixel_begin, pixel_begin + pass.size()), each of
  // which took `samples` samples. A pass may arrive in several launches over disjoint pixel
  // ranges; samples_per_pixel() advances once, when the launches of the pass have covered
  // pixel_count() pixels. Contract: the launches of one pass share `samples`, cover each pixel
  // once, and do not interleave with another pass (throws std::logic_error otherwise).
  void add_pass(const std::vector<GpuPixelPass>& pass, size_t pixel_begin, uint32_t samples);
  // True between passes (no pass partly added): the film is then a consistent image.
  bool between_passes() const { return pending_pixels_ == 0; }

  // Mean radiance, RGB interleaved, row 0 at the top. Pixels without a valid sample are 0.
  std::vector<float> mean_rgb() const;
  // Variance of the pixel mean per channel: s^2 / n with s^2 the unbiased sample variance.
  // Pixels with fewer than two valid samples get 0.
  std::vector<float> variance_rgb() const;
  // Both, as the statistics read a render (tools/image_compare.h, tools/tradeoff.h).
  MeanVarianceImage mean_variance() const { return {width_, height_, mean_rgb(), variance_rgb()}; }

  // Samples per pixel taken so far (the same for every pixel after whole passes).
  uint64_t samples_per_pixel() const { return samples_per_pixel_; }
  uint64_t total_samples() const { return total_samples_; }
  uint64_t total_segments() const { return total_segments_; }
  // Samples dropped because their radiance had a NaN or Inf channel.
  uint64_t dropped_samples() const { return dropped_samples_; }

  // The accumulated state, for checkpoints (render/checkpoint.h). Sums are RGB interleaved per
  // pixel; valid counts one per pixel.
  struct Totals {
    uint64_t samples_per_pixel = 0, total_samples = 0, total_segments = 0, dropped_samples = 0;
  };
  const std::vector<double>& sums() const { return sum_; }
  const std::vector<double>& sums_of_squares() const { return sum_sq_; }
  const std::vector<double>& valid_counts() const { return valid_; }
  Totals totals() const;
  // A film between passes with the given state; throws std::invalid_argument on sizes that do
  // not match width x height.
  static Film restore(int width, int height, std::vector<double> sum, std::vector<double> sum_sq,
                      std::vector<double> valid, const Totals& totals);

 private:
  // Advances samples_per_pixel_ once the current pass has covered every pixel.
  void track_pass_coverage(size_t pixels, uint32_t samples);

  int width_, height_;
  std::vector<double> sum_;     // 3 per pixel
  std::vector<double> sum_sq_;  // 3 per pixel
  std::vector<double> valid_;   // valid samples per pixel
  uint64_t samples_per_pixel_ = 0;
  uint64_t total_samples_ = 0;
  uint64_t total_segments_ = 0;
  uint64_t dropped_samples_ = 0;
  size_t pending_pixels_ = 0;     // pixels of the current pass added so far
  uint32_t pending_samples_ = 0;  // samples per pixel of the current pass
};

}  // namespace clpt
