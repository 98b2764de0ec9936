#include "render/film.h"

#include <algorithm>

namespace clpt {

Film::Film(int width, int height)
    : width_(width),
      height_(height),
      sum_(size_t(width) * height * 3, 0.0),
      sum_sq_(size_t(width) * height * 3, 0.0),
      valid_(size_t(width) * height, 0.0) {}

void Film::add_pass(const std::vector<GpuPixelPass>& pass, size_t pixel_begin, uint32_t samples) {
  for (size_t i = 0; i < pass.size(); ++i) {
    const GpuPixelPass& p = pass[i];
    const size_t pixel = pixel_begin + i;
    for (int c = 0; c < 3; ++c) {
      sum_[pixel * 3 + c] += p.sum[c];
      sum_sq_[pixel * 3 + c] += p.sum_sq[c];
    }
    valid_[pixel] += p.valid_samples;
    total_segments_ += p.segments;
    dropped_samples_ += samples - static_cast<uint64_t>(p.valid_samples);
  }
  total_samples_ += uint64_t(samples) * pass.size();
  // Whole-image passes advance the per-pixel count; partial launches are completed by the caller.
  if (pixel_begin == 0 && pass.size() == pixel_count()) samples_per_pixel_ += samples;
}

std::vector<float> Film::mean_rgb() const {
  std::vector<float> out(sum_.size(), 0.0f);
  for (size_t p = 0; p < valid_.size(); ++p) {
    if (valid_[p] <= 0) continue;
    for (int c = 0; c < 3; ++c) out[p * 3 + c] = static_cast<float>(sum_[p * 3 + c] / valid_[p]);
  }
  return out;
}

std::vector<float> Film::variance_rgb() const {
  std::vector<float> out(sum_.size(), 0.0f);
  for (size_t p = 0; p < valid_.size(); ++p) {
    const double n = valid_[p];
    if (n < 2) continue;
    for (int c = 0; c < 3; ++c) {
      const double s = sum_[p * 3 + c];
      const double sample_variance = std::max(0.0, (sum_sq_[p * 3 + c] - s * s / n) / (n - 1));
      out[p * 3 + c] = static_cast<float>(sample_variance / n);
    }
  }
  return out;
}

}  // namespace clpt
