// The one decision of what the next pass is (pass_schedule.h).
#include "render/pass_schedule.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "render/adaptive_sampling.h"
#include "render/limits.h"

namespace clpt {
namespace {

uint64_t round_up(uint64_t n, uint64_t g) { return (n + g - 1) / g * g; }

}  // namespace

uint64_t half0_end(uint64_t spp, uint32_t granularity, bool power_of_two_halves) {
  const uint64_t g = std::max<uint32_t>(granularity, 1);
  const uint64_t share = round_up((spp + 1) / 2, g);
  if (!power_of_two_halves) return share;
  uint64_t power = 1;
  while (power < share) power *= 2;
  return std::min(round_up(power, g), spp);
}

uint64_t check_ladder_at_or_above(uint64_t spp, uint32_t granularity) {
  const uint64_t g = std::max<uint32_t>(granularity, 1);
  uint64_t point = 2 * round_up(std::max<uint64_t>(8, g), g);
  while (point < spp && point < kMaxSpp) point += 2 * round_up(std::max<uint64_t>(1, point / 16), g);
  return std::min(point, kMaxSpp);
}

uint32_t next_pass_samples(uint64_t done, uint64_t target, double samples_per_pixel_per_s,
                           double target_s, uint32_t granularity) {
  double want = samples_per_pixel_per_s > 0 ? samples_per_pixel_per_s * target_s : granularity;
  want = std::clamp(want, double(granularity), double(kMaxSamplesPerPass));
  uint64_t n = uint64_t(want) / granularity * granularity;
  if (target > 0) n = std::min<uint64_t>(n, target - done);
  return static_cast<uint32_t>(std::max<uint64_t>(n, 1));
}

uint64_t predicted_spp_for(const ErrorEstimate& estimate, uint64_t spp, double target_error) {
  if (!estimate.valid || !(target_error > 0)) return 0;
  const double ratio = estimate.relative_rmse_upper / target_error;
  return uint64_t(std::min(double(kMaxSpp), std::ceil(double(spp) * ratio * ratio)));
}

namespace {

// Adaptive mode's passes (adaptive_sampling.h), sized by the image alone: below the ladder's first
// point, uniform passes fill each half to half of it (or to the render's end); in a round, half 1's
// slots, then half 0's uniform passes.
void plan_adaptive_pass(const Film& film, uint64_t stop_spp, uint32_t g, bool power_of_two_halves, uint32_t device_limit,
                        NextPass& next) {
  const uint64_t pixels = std::max<uint64_t>(film.pixel_count(), 1);
  const uint64_t uniform_spp = std::min<uint64_t>(
      round_up(std::max<uint64_t>(1, (kAdaptivePassSamples + pixels - 1) / pixels), g), std::max(g, device_limit / g * g));
  const uint64_t half_spp[2] = {film.half_samples_per_pixel(0), film.half_samples_per_pixel(1)};
  const std::optional<AdaptiveRound> round = adaptive_round(film, stop_spp, g);
  uint64_t half_end[2];
  if (round) {
    const uint64_t half1_end_total = pixels * round->half1_end;
    if (film.half1_total_samples() < half1_end_total) {
      next.adaptive = true;
      next.half = 1;
      next.samples = g;
      next.slot_begin = (film.half1_total_samples() - pixels * (round->start_spp / 2)) / g;
      const uint64_t left = (half1_end_total - film.half1_total_samples()) / g;
      next.slot_count = static_cast<uint32_t>(std::min<uint64_t>(left, std::max<uint64_t>(1, kAdaptivePassSamples / g)));
      next.sample_begin = 0;
      return;
    }
    half_end[0] = round->half0_end;
    half_end[1] = round->half1_end;
  } else {
    const uint64_t first = check_ladder_at_or_above(0, g);
    half_end[0] = stop_spp < first ? half0_end(stop_spp, g, power_of_two_halves) : first / 2;
    half_end[1] = stop_spp < first ? stop_spp - half_end[0] : first / 2;
  }
  next.half = half_spp[1] < half_end[1] && half_spp[1] < half_spp[0] ? 1 : 0;
  if (half_spp[next.half] >= half_end[next.half]) next.half ^= 1;
  next.sample_begin = static_cast<uint32_t>((uint64_t(next.half) << CLPT_SAMPLE_STREAM_BIT) + half_spp[next.half]);
  next.samples = static_cast<uint32_t>(std::min(uniform_spp, half_end[next.half] - half_spp[next.half]));
}

}  // namespace

uint64_t stop_spp(const PassRequest& request) {
  return request.target_spp ? std::min(request.target_spp, kMaxSpp) : kMaxSpp;
}

NextPass plan_next_pass(const Film& film, const PassRequest& request, const PassMeasurements& measured,
                        PassScheduleState& state) {
  return plan_next_pass(film, estimate_error(film), request, measured, state);
}

NextPass plan_next_pass(const Film& film, const ErrorEstimate& estimate, const PassRequest& request,
                        const PassMeasurements& measured, PassScheduleState& state) {
  NextPass next;
  const uint64_t spp = film.samples_per_pixel();
  const uint64_t stop_spp = clpt::stop_spp(request);
  const uint32_t g = std::max<uint32_t>(request.granularity, 1);
  next.estimate = estimate;
  next.half = film.next_half();
  const uint64_t half_spp[2] = {film.half_samples_per_pixel(0), film.half_samples_per_pixel(1)};
  next.sample_begin = static_cast<uint32_t>((uint64_t(next.half) << CLPT_SAMPLE_STREAM_BIT) + half_spp[next.half]);
  const bool target_mode = request.target_error > 0;
  if (target_mode) next.predicted_spp = predicted_spp_for(next.estimate, spp, request.target_error);

  if (spp >= stop_spp) {
    next.stop = StopReason::SampleCount;
    return next;
  }
  if (request.time_limit_s > 0 && measured.passes > 0 && measured.elapsed_s >= request.time_limit_s) {
    next.stop = StopReason::TimeLimit;
    return next;
  }
  if (target_mode) {
    if (state.next_check_spp == 0) state.next_check_spp = check_ladder_at_or_above(spp, g);
    if (spp >= state.next_check_spp && half_spp[0] == half_spp[1]) {
      if (next.estimate.valid && next.estimate.relative_rmse_upper <= request.target_error) {
        next.stop = StopReason::TargetError;
        return next;
      }
      // Jump towards the predicted count, a little short of it so the check lands near it, and at
      // most by half the samples so far: an early estimate from few samples is noisy, and a jump
      // too far cannot be undone (true error at the stop >= target / sqrt(1.5) from the jump alone).
      const uint64_t aim = std::clamp<uint64_t>(uint64_t(0.95 * double(next.predicted_spp)), spp + 1, spp + spp / 2);
      state.next_check_spp = check_ladder_at_or_above(aim, g);
    }
  }

  const uint32_t device_limit = measured.max_samples_per_pass ? measured.max_samples_per_pass : kMaxSamplesPerPass;
  if (request.adaptive) {
    plan_adaptive_pass(film, stop_spp, g, request.power_of_two_halves, device_limit, next);
    return next;
  }

  // Pass size: about pass_target_s at the measured rate (less when the time budget ends sooner).
  double pass_s = request.pass_target_s;
  if (request.time_limit_s > 0) pass_s = std::min(pass_s, std::max(0.0, request.time_limit_s - measured.elapsed_s));
  uint64_t n = next_pass_samples(spp, stop_spp, measured.samples_per_pixel_per_s, pass_s, g);
  // Each half fills up to its end, so that a render of S samples ends with halves of half0_end(S)
  // and the rest whatever the pass sizes were: the samples drawn, and so the image, depend on S
  // alone. The pass goes to the smaller half (half 0 on a tie) unless that one is full. (A
  // resumed render whose halves were split otherwise may pass an end; it still stops at S.)
  const uint64_t end0 = half0_end(stop_spp, g, request.power_of_two_halves);
  const uint64_t half_end[2] = {end0, stop_spp - end0};
  const bool half0_open = half_spp[0] < half_end[0];
  next.half = half0_open && (half_spp[0] <= half_spp[1] || half_spp[1] >= half_end[1]) ? 0 : 1;
  next.sample_begin = static_cast<uint32_t>((uint64_t(next.half) << CLPT_SAMPLE_STREAM_BIT) + half_spp[next.half]);
  if (half_spp[next.half] < half_end[next.half]) n = std::min(n, half_end[next.half] - half_spp[next.half]);
  // The smaller half only catches up: at equal halves the estimate is exact (error_estimate.h).
  const uint64_t other = half_spp[next.half ^ 1];
  if (half_spp[next.half] < other) n = std::min(n, other - half_spp[next.half]);
  // Target error: each half reaches half the next check point.
  if (target_mode && state.next_check_spp > spp && state.next_check_spp / 2 > half_spp[next.half])
    n = std::min(n, state.next_check_spp / 2 - half_spp[next.half]);
  n = std::min<uint64_t>(n, std::max(g, device_limit / g * g));
  n = std::min(n, stop_spp - spp);
  next.samples = static_cast<uint32_t>(std::max<uint64_t>(n, 1));
  return next;
}

const char* stop_reason_name(StopReason reason) {
  switch (reason) {
    case StopReason::None: return "none";
    case StopReason::SampleCount: return "sample count";
    case StopReason::TimeLimit: return "time limit";
    case StopReason::TargetError: return "target error";
  }
  return "?";
}

}  // namespace clpt
