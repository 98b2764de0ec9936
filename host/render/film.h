// The host film: per-pixel sums of sample radiance and of its square, in double, added pass by
// pass from the device's float pass statistics. It yields the pixel mean and the variance of
// that mean, per channel. Every pass also goes, whole, into one of two half-films (the half with
// fewer samples per pixel; half 0 on a tie), whose difference is an unbiased measure of the
// image's error whatever the sampler's stratification (render/error_estimate.h). An adaptive
// pass (render/adaptive_sampling.h) goes to half 1 and gives each pixel its own number of
// samples, one or more slots of `samples` each; half 0 stays uniform.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "kernels/types.h"
#include "util/large_pages.h"

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
  // An adaptive pass passes its `slots`: the launch's entry i is then slot pixel_begin + i, added
  // to that slot's pixel in half 1, and the pass is complete when its launches have covered
  // slots->size() slots. `half`: the half a uniform pass goes to (-1: next_half()); the pass
  // loop gives the half its sample indices came from (sample_begin's CLPT_SAMPLE_STREAM_BIT).
  void add_pass(const std::vector<GpuPixelPass>& pass, size_t pixel_begin, uint32_t samples,
                const std::vector<GpuSampleSlot>* slots = nullptr, int half = -1);
  // The first-hit layers (render/aov_set.h, docs/aovs.md): a film that has them (enable_aovs,
  // before any pass) adds each launch's layer sums (Renderer::aov_sums: CLPT_AOV_CHANNELS floats
  // per entry of `pass`, entries as add_pass takes them, `slots` alike) with add_aovs, called for
  // every launch beside add_pass; the mean of each pixel is over the same samples as its
  // radiance (every sample, NaN/Inf ones too: their layers are finite). Not in checkpoints.
  void enable_aovs();
  bool has_aovs() const { return aov_enabled_; }
  void add_aovs(const std::vector<float>& sums, size_t pixel_begin, uint32_t samples,
                const std::vector<GpuSampleSlot>* slots = nullptr);
  // Per pixel the mean of each layer channel, CLPT_AOV_CHANNELS floats a pixel
  // (kernels/aov_channels.h), row 0 at the top; 0 for a pixel without samples. Empty without
  // the layers.
  std::vector<float> aov_means() const;

  // True between passes (no pass partly added): the film is then a consistent image.
  bool between_passes() const { return pending_pixels_ == 0; }

  // Mean radiance, RGB interleaved, row 0 at the top. Pixels without a valid sample are 0.
  std::vector<float> mean_rgb() const;
  // Variance of the pixel mean per channel: s^2 / n with s^2 the unbiased sample variance.
  // Pixels with fewer than two valid samples get 0.
  std::vector<float> variance_rgb() const;
  // Both, as the statistics read a render (tools/image_compare.h, tools/tradeoff.h).
  MeanVarianceImage mean_variance() const { return {width_, height_, mean_rgb(), variance_rgb()}; }

  // Samples per pixel taken so far: half 0's plus half 1's (half_samples_per_pixel). The same
  // for every pixel after whole uniform passes; the mean over pixels with adaptive passes.
  uint64_t samples_per_pixel() const { return samples_per_pixel_; }
  uint64_t total_samples() const { return total_samples_; }
  uint64_t total_segments() const { return total_segments_; }
  // Samples dropped because their radiance had a NaN or Inf channel.
  uint64_t dropped_samples() const { return dropped_samples_; }

  // The two half-films. Half 1's sums, sums of squares, valid counts and samples are stored;
  // half 0 is the whole film less half 1. half_samples_per_pixel(h): samples per pixel of the
  // whole passes added to half h; for half 1 the mean over pixels, rounded down, of
  // half1_samples() (every pixel's own count, NaN/Inf samples included: its next sample index
  // is 2^31 + that count). Half 1's samples have indices from 2^31 (pass_schedule.h).
  // next_half(): the half with fewer samples (0 on a tie), fixed by the film's own state, so every
  // device and every resumed render agrees on it; the pass schedule sends a pass there unless
  // that half is full (pass_schedule.h, half0_end).
  uint64_t half_samples_per_pixel(int half) const { return half_spp_[half & 1]; }
  int next_half() const { return half_spp_[1] < half_spp_[0] ? 1 : 0; }
  const LargeVector<double>& half1_sums() const { return half1_sum_; }
  const LargeVector<double>& half1_sums_of_squares() const { return half1_sum_sq_; }
  const LargeVector<double>& half1_valid_counts() const { return half1_valid_; }
  const LargeVector<uint32_t>& half1_samples() const { return half1_samples_; }
  uint64_t half1_total_samples() const { return half1_total_; }

  // The accumulated state, for checkpoints (render/checkpoint.h). Sums are RGB interleaved per
  // pixel; valid counts one per pixel.
  struct Totals {
    uint64_t samples_per_pixel = 0, total_samples = 0, total_segments = 0, dropped_samples = 0;
  };
  const LargeVector<double>& sums() const { return sum_; }
  const LargeVector<double>& sums_of_squares() const { return sum_sq_; }
  const LargeVector<double>& valid_counts() const { return valid_; }
  Totals totals() const;
  // A film between passes with the given state; throws std::invalid_argument on sizes that do
  // not match width x height.
  static Film restore(int width, int height, std::vector<double> sum, std::vector<double> sum_sq,
                      std::vector<double> valid, const Totals& totals);
  // The half-films of a restored film: half 1's sums (3 per pixel), valid counts, sums of squares
  // (3 per pixel; empty: unknown, zeros, as in a version-2 checkpoint, which only non-adaptive
  // renders wrote) and per-pixel samples (empty: half1_spp each, a uniform half). A film
  // restored without them (a version-1 checkpoint) has everything in half 0, and the next
  // passes go to half 1 until it catches up. Throws std::invalid_argument on sizes that do not
  // match, or half 1 holding more samples than the film.
  void restore_halves(std::vector<double> half1_sum, std::vector<double> half1_valid, uint64_t half1_spp,
                      std::vector<double> half1_sum_sq = {}, std::vector<uint32_t> half1_samples = {});

 private:
  // Advances samples_per_pixel_ once the current pass has covered every pixel (a uniform pass)
  // or every slot (`pass_slots` of an adaptive pass).
  void track_pass_coverage(size_t pixels, uint32_t samples, size_t pass_slots);
  // half_spp_[1] and samples_per_pixel_ from half1_total_ and half_spp_[0].
  void update_half1_spp();

  int width_, height_;
  LargeVector<double> sum_;     // 3 per pixel
  LargeVector<double> sum_sq_;  // 3 per pixel
  LargeVector<double> valid_;   // valid samples per pixel
  LargeVector<double> half1_sum_;    // 3 per pixel: sums of the passes of half 1
  LargeVector<double> half1_sum_sq_;  // 3 per pixel: sums of squares of the passes of half 1
  LargeVector<double> half1_valid_;  // valid samples per pixel in half 1
  LargeVector<uint32_t> half1_samples_;  // samples per pixel in half 1, valid or not
  uint64_t half1_total_ = 0;             // their sum over pixels
  uint64_t half_spp_[2] = {0, 0};    // samples per pixel of each half's whole passes
  bool aov_enabled_ = false;
  LargeVector<double> aov_sum_;      // CLPT_AOV_CHANNELS per pixel: sums of the first-hit layers
  LargeVector<double> aov_samples_;  // samples per pixel those sums hold
  uint64_t samples_per_pixel_ = 0;
  uint64_t total_samples_ = 0;
  uint64_t total_segments_ = 0;
  uint64_t dropped_samples_ = 0;
  size_t pending_pixels_ = 0;     // pixels (slots, of an adaptive pass) of the current pass added so far
  uint32_t pending_samples_ = 0;  // samples per pixel of the current pass
  int pending_half_ = 0;          // the half the current pass goes to
};

}  // namespace clpt
