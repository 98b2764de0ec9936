#include "render/work_queue.h"

#include <algorithm>
#include <cmath>

namespace clpt {

uint32_t PixelRangeQueue::remaining() const {
  uint32_t n = end_ - next_;
  for (const PixelRange& r : given_back_) n += r.count;
  return n;
}

PixelRange PixelRangeQueue::take(uint32_t count) {
  count = std::max(count, 1u);
  if (!given_back_.empty()) {
    PixelRange& back = given_back_.back();
    const PixelRange out{back.begin, std::min(count, back.count)};
    back.begin += out.count;
    back.count -= out.count;
    if (back.count == 0) given_back_.pop_back();
    return out;
  }
  const PixelRange out{next_, std::min(count, end_ - next_)};
  next_ += out.count;
  return out;
}

void PixelRangeQueue::give_back(PixelRange range) {
  if (range.count > 0) given_back_.push_back(range);
}

uint32_t balanced_range_pixels(uint32_t launch, uint32_t remaining, double share, uint32_t min_pixels) {
  if (remaining == 0) return 0;
  double n = std::max(1u, launch);
  if (share < 1) n = std::min(n, std::max(double(min_pixels), std::ceil(share * remaining)));
  return static_cast<uint32_t>(std::clamp(n, 1.0, double(remaining)));
}

uint32_t next_launch_pixels(const LaunchSizing& sizing, uint32_t remaining, uint32_t samples,
                            double pixel_samples_per_s, uint32_t previous) {
  if (remaining == 0) return 0;
  const double max_pixels = std::max(1u, std::min(sizing.max_pixels, sizing.max_jobs / std::max(1u, samples)));
  double n = max_pixels;
  if (sizing.target_s > 0) {
    n = pixel_samples_per_s > 0 ? pixel_samples_per_s * sizing.target_s / std::max(1u, samples)
                                : double(sizing.first_pixels);
    if (previous > 0) n = std::min(n, double(previous) * kMaxLaunchGrowth);
    n = std::clamp(n, 1.0, max_pixels);
  }
  const uint32_t pixels = static_cast<uint32_t>(n);
  if (pixels >= remaining || (remaining - pixels < pixels / 4 && remaining <= max_pixels)) return remaining;
  return pixels;
}

}  // namespace clpt
