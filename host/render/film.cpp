#include "render/film.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>

#include "kernels/aov_channels.h"

namespace clpt {

Film::Film(int width, int height)
    : width_(width),
      height_(height),
      sum_(size_t(width) * height * 3),
      sum_sq_(size_t(width) * height * 3),
      valid_(size_t(width) * height),
      half1_sum_(size_t(width) * height * 3),
      half1_sum_sq_(size_t(width) * height * 3),
      half1_valid_(size_t(width) * height),
      half1_samples_(size_t(width) * height) {}

void Film::add_pass(const std::vector<GpuPixelPass>& pass, size_t pixel_begin, uint32_t samples,
                    const std::vector<GpuSampleSlot>* slots, int half) {
  // A new pass: all of it goes to one half.
  if (pending_pixels_ == 0) pending_half_ = slots ? 1 : half < 0 ? next_half() : (half & 1);
  if (slots && pending_half_ != 1) throw std::logic_error("Film::add_pass: an adaptive launch inside a uniform pass");
  if (slots && pixel_begin + pass.size() > slots->size())
    throw std::logic_error("Film::add_pass: a launch past the adaptive pass's slots");
  const bool to_half1 = pending_half_ == 1;
  for (size_t i = 0; i < pass.size(); ++i) {
    const GpuPixelPass& p = pass[i];
    const size_t pixel = slots ? (*slots)[pixel_begin + i].pixel : pixel_begin + i;
    if (pixel >= pixel_count()) throw std::logic_error("Film::add_pass: a slot's pixel is outside the image");
    for (int c = 0; c < 3; ++c) {
      sum_[pixel * 3 + c] += p.sum[c];
      sum_sq_[pixel * 3 + c] += p.sum_sq[c];
    }
    valid_[pixel] += p.valid_samples;
    if (to_half1) {
      for (int c = 0; c < 3; ++c) {
        half1_sum_[pixel * 3 + c] += p.sum[c];
        half1_sum_sq_[pixel * 3 + c] += p.sum_sq[c];
      }
      half1_valid_[pixel] += p.valid_samples;
      half1_samples_[pixel] += samples;
    }
    total_segments_ += p.segments;
    dropped_samples_ += samples - static_cast<uint64_t>(p.valid_samples);
  }
  total_samples_ += uint64_t(samples) * pass.size();
  if (to_half1) half1_total_ += uint64_t(samples) * pass.size();
  track_pass_coverage(pass.size(), samples, slots ? slots->size() : pixel_count());
}

void Film::enable_aovs() {
  aov_enabled_ = true;
  aov_sum_.assign(pixel_count() * CLPT_AOV_CHANNELS, 0.0);
  aov_samples_.assign(pixel_count(), 0.0);
}

void Film::add_aovs(const std::vector<float>& sums, size_t pixel_begin, uint32_t samples,
                    const std::vector<GpuSampleSlot>* slots) {
  if (!aov_enabled_) throw std::logic_error("Film::add_aovs: the film has no first-hit layers");
  if (sums.size() % CLPT_AOV_CHANNELS != 0) throw std::logic_error("Film::add_aovs: a partial entry");
  const size_t entries = sums.size() / CLPT_AOV_CHANNELS;
  if (slots && pixel_begin + entries > slots->size())
    throw std::logic_error("Film::add_aovs: a launch past the adaptive pass's slots");
  for (size_t i = 0; i < entries; ++i) {
    const size_t pixel = slots ? (*slots)[pixel_begin + i].pixel : pixel_begin + i;
    if (pixel >= pixel_count()) throw std::logic_error("Film::add_aovs: a pixel outside the image");
    for (size_t c = 0; c < CLPT_AOV_CHANNELS; ++c)
      aov_sum_[pixel * CLPT_AOV_CHANNELS + c] += double(sums[i * CLPT_AOV_CHANNELS + c]);
    aov_samples_[pixel] += samples;
  }
}

std::vector<float> Film::aov_means() const {
  std::vector<float> out(aov_sum_.size());
  for (size_t p = 0; p < aov_samples_.size(); ++p)
    for (size_t c = 0; c < CLPT_AOV_CHANNELS; ++c)
      out[p * CLPT_AOV_CHANNELS + c] =
          aov_samples_[p] > 0 ? float(aov_sum_[p * CLPT_AOV_CHANNELS + c] / aov_samples_[p]) : 0.0f;
  return out;
}

void Film::track_pass_coverage(size_t pixels, uint32_t samples, size_t pass_slots) {
  if (pending_pixels_ > 0 && samples != pending_samples_)
    throw std::logic_error("Film::add_pass: a launch with " + std::to_string(samples) +
                           " samples inside a pass of " + std::to_string(pending_samples_));
  pending_samples_ = samples;
  pending_pixels_ += pixels;
  if (pending_pixels_ > pass_slots) throw std::logic_error("Film::add_pass: pass covers too many pixels");
  if (pending_pixels_ == pass_slots) {
    if (pending_half_ == 0) half_spp_[0] += samples;
    update_half1_spp();
    pending_pixels_ = 0;
  }
}

void Film::update_half1_spp() {
  half_spp_[1] = pixel_count() ? half1_total_ / pixel_count() : 0;
  samples_per_pixel_ = half_spp_[0] + half_spp_[1];
}

Film::Totals Film::totals() const {
  return {samples_per_pixel_, total_samples_, total_segments_, dropped_samples_};
}

Film Film::restore(int width, int height, std::vector<double> sum, std::vector<double> sum_sq,
                   std::vector<double> valid, const Totals& totals) {
  Film film(0, 0);
  const size_t pixels = size_t(width) * size_t(height);
  if (width < 0 || height < 0 || sum.size() != pixels * 3 || sum_sq.size() != pixels * 3 ||
      valid.size() != pixels)
    throw std::invalid_argument("Film::restore: arrays do not match the image size");
  film.width_ = width;
  film.height_ = height;
  film.sum_.assign(sum.begin(), sum.end());
  film.sum_sq_.assign(sum_sq.begin(), sum_sq.end());
  film.valid_.assign(valid.begin(), valid.end());
  film.samples_per_pixel_ = totals.samples_per_pixel;
  film.total_samples_ = totals.total_samples;
  film.total_segments_ = totals.total_segments;
  film.dropped_samples_ = totals.dropped_samples;
  film.half1_sum_.assign(pixels * 3, 0.0);
  film.half1_sum_sq_.assign(pixels * 3, 0.0);
  film.half1_valid_.assign(pixels, 0.0);
  film.half1_samples_.assign(pixels, 0);
  film.half1_total_ = 0;
  film.half_spp_[0] = totals.samples_per_pixel;
  film.half_spp_[1] = 0;
  return film;
}

void Film::restore_halves(std::vector<double> half1_sum, std::vector<double> half1_valid, uint64_t half1_spp,
                          std::vector<double> half1_sum_sq, std::vector<uint32_t> half1_samples) {
  if (half1_sum_sq.empty()) half1_sum_sq.assign(sum_sq_.size(), 0.0);
  if (half1_samples.empty()) half1_samples.assign(valid_.size(), static_cast<uint32_t>(std::min<uint64_t>(half1_spp, UINT32_MAX)));
  uint64_t total = 0;
  for (uint32_t n : half1_samples) total += n;
  if (half1_sum.size() != sum_.size() || half1_valid.size() != valid_.size() || half1_sum_sq.size() != sum_sq_.size() ||
      half1_samples.size() != valid_.size() || half1_spp > samples_per_pixel_ ||
      (pixel_count() && total / pixel_count() != half1_spp))
    throw std::invalid_argument("Film::restore_halves: half-film does not match the film");
  half1_sum_.assign(half1_sum.begin(), half1_sum.end());
  half1_sum_sq_.assign(half1_sum_sq.begin(), half1_sum_sq.end());
  half1_valid_.assign(half1_valid.begin(), half1_valid.end());
  half1_samples_.assign(half1_samples.begin(), half1_samples.end());
  half1_total_ = total;
  half_spp_[0] = samples_per_pixel_ - half1_spp;
  update_half1_spp();
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
