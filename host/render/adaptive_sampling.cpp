// The rounds and slot allocation of adaptive sampling (adaptive_sampling.h).
#include "render/adaptive_sampling.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/pass_schedule.h"

namespace clpt {

std::optional<AdaptiveRound> adaptive_round(const Film& film, uint64_t stop_spp, uint32_t granularity) {
  const uint64_t g = std::max<uint32_t>(granularity, 1);
  const uint64_t first = check_ladder_at_or_above(0, granularity);
  const uint64_t h0 = film.half_samples_per_pixel(0), h1 = film.half_samples_per_pixel(1);
  if (h0 < first / 2 || h1 < first / 2 || first >= stop_spp) return std::nullopt;  // the uniform start
  uint64_t start = first;
  while (start < stop_spp) {
    AdaptiveRound r;
    r.start_spp = start;
    r.end_spp = std::min(stop_spp, check_ladder_at_or_above(start + 1, granularity));
    r.half1_end = (r.end_spp + 2 * g - 1) / (2 * g) * g;
    r.half0_end = r.end_spp - r.half1_end;
    if (h0 < r.half0_end) return r;
    start = r.end_spp;
  }
  return std::nullopt;
}

std::vector<double> adaptive_weights(const Film& film) {
  const int w = film.width(), h = film.height();
  const size_t pixels = film.pixel_count();
  const auto& sum = film.sums();
  const auto& sum_sq = film.sums_of_squares();
  const auto& valid = film.valid_counts();
  const auto& sum1 = film.half1_sums();
  const auto& sum_sq1 = film.half1_sums_of_squares();
  const auto& valid1 = film.half1_valid_counts();
  // Half 0's per-sample variance per pixel, the mean over channels; -1: fewer than 2 samples.
  std::vector<double> variance(pixels, -1.0);
  for (size_t p = 0; p < pixels; ++p) {
    const double n0 = valid[p] - valid1[p];
    if (n0 < 2) continue;
    double v = 0;
    for (int c = 0; c < 3; ++c) {
      const double s = sum[p * 3 + c] - sum1[p * 3 + c];
      const double sq = sum_sq[p * 3 + c] - sum_sq1[p * 3 + c];
      v += std::max(0.0, (sq - s * s / n0) / (n0 - 1));
    }
    variance[p] = v / 3;
  }
  double known_sum = 0;
  size_t known = 0;
  for (double v : variance)
    if (v >= 0) known_sum += v, ++known;
  const double fallback = known ? known_sum / double(known) : 0;
  // The weight of a pixel: the standard deviation over its neighbours, itself excluded.
  std::vector<double> weight(pixels, 0.0);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double v = 0;
      int n = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
          const double vq = variance[size_t(ny) * size_t(w) + size_t(nx)];
          if (vq >= 0) v += vq, ++n;
        }
      weight[size_t(y) * size_t(w) + size_t(x)] = std::sqrt(n ? v / n : fallback);
    }
  return weight;
}

std::vector<uint32_t> adaptive_slot_counts(const Film& film, uint64_t slot_total) {
  const size_t pixels = film.pixel_count();
  std::vector<double> weight = adaptive_weights(film);
  // The cap is a multiple of the median: a mean would follow the outliers it is meant to cap.
  std::vector<double> sorted = weight;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  double scale = sorted.empty() ? 0 : sorted[sorted.size() / 2];
  if (!(scale > 0)) {  // most of the image noiseless (a black background): the mean of the rest
    double positive = 0;
    size_t n = 0;
    for (double wp : weight)
      if (wp > 0 && std::isfinite(wp)) positive += wp, ++n;
    scale = n ? positive / double(n) : 0;
  }
  double total = 0;
  for (double& wp : weight) wp = std::isfinite(wp) ? std::min(wp, kAdaptiveWeightCap * scale) : kAdaptiveWeightCap * scale;
  for (double wp : weight) total += wp;
  if (!(total > 0)) std::fill(weight.begin(), weight.end(), 1.0), total = double(pixels);  // no noise seen: uniform
  std::vector<uint32_t> counts(pixels, 0);
  std::vector<std::pair<double, size_t>> remainders(pixels);
  uint64_t given = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const double share = double(slot_total) * weight[p] / total;
    const double whole = std::floor(share);
    counts[p] = static_cast<uint32_t>(whole);
    given += counts[p];
    remainders[p] = {share - whole, p};
  }
  std::sort(remainders.begin(), remainders.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first > b.first : a.second < b.second;
  });
  for (size_t i = 0; given < slot_total; i = (i + 1) % pixels, ++given) ++counts[remainders[i].second];
  while (given > slot_total) {  // float shares that summed past the total: take from the largest
    const size_t p = size_t(std::max_element(counts.begin(), counts.end()) - counts.begin());
    --counts[p];
    --given;
  }
  return counts;
}

std::vector<GpuSampleSlot> adaptive_pass_slots(const Film& film, const std::vector<uint32_t>& counts, uint32_t granularity,
                                               uint64_t first, uint64_t count) {
  std::vector<GpuSampleSlot> slots;
  slots.reserve(size_t(count));
  const auto& taken = film.half1_samples();
  uint64_t at = 0;  // the table's index of pixel p's first slot
  for (size_t p = 0; p < counts.size() && slots.size() < count; at += counts[p], ++p) {
    if (at + counts[p] <= first) continue;
    const uint64_t begin = std::max(at, first);
    const uint64_t end = std::min<uint64_t>(at + counts[p], first + count);
    for (uint64_t k = begin; k < end; ++k) {
      const uint64_t index = (uint64_t(1) << CLPT_SAMPLE_STREAM_BIT) + taken[p] + (k - begin) * granularity;
      slots.push_back(GpuSampleSlot{static_cast<uint32_t>(p), static_cast<uint32_t>(index)});
    }
  }
  return slots;
}

std::vector<GpuSampleSlot> AdaptiveSlotTable::pass_slots(const Film& film, const NextPass& next,
                                                         const PassRequest& request) {
  const std::optional<AdaptiveRound> round = adaptive_round(film, stop_spp(request), request.granularity);
  if (!round) throw std::logic_error("AdaptiveSlotTable: an adaptive pass outside a round");
  if (counts_.empty() || round_start_ != round->start_spp) {
    counts_ = adaptive_slot_counts(film, round->slot_total(film.pixel_count(), request.granularity));
    round_start_ = round->start_spp;
  }
  return adaptive_pass_slots(film, counts_, request.granularity, next.slot_begin, next.slot_count);
}

}  // namespace clpt
