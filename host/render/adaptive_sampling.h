// Adaptive sampling (`--adaptive`): after a uniform start, each round of the render spends half 1's
// samples where half 0 says the error is largest, and keeps half 0 uniform, a floor under every
// pixel. Docs: docs/target-error.md "Adaptive sampling".
//
// Rounds. The render is cut at the points of the check-point ladder (pass_schedule.h: 16, 18, 20,
// ... for jitter and Sobol), where both halves hold equal samples; below the first point both
// halves are uniform. A round from ladder point L to the next point E (or to the render's last
// sample count) first gives half 1 its share, P (h1 - L/2) samples for P pixels, in slots of g
// samples (g: the sampler's granularity) distributed over the pixels by adaptive_slot_counts, then
// gives half 0 its share in uniform passes. At a ladder point E: h1 = h0 = E/2; at a last count
// S: h1 = g ceil(S / 2g) and h0 = S - h1.
//
// Why the image stays unbiased. A pixel's value is the mean of its samples, n0 of half 0 (uniform:
// a number that depends on no sample) and N1 of half 1. N1 is the pixel's weight, decided from
// half 0's samples of its eight neighbours, never of the pixel itself, times the round's budget
// over the sum of all P weights; the counter-based RNG makes every pixel's samples independent of
// every other pixel's. So the pixel's own samples reach its N1 only through that sum, where they
// move 8 of the P weights: a mean of a number of independent samples that does not depend on
// them is unbiased, and the coupling through the sum is of order 1/P, the order of the
// --target-error stop (which ends every pixel at a count the whole image decided). Half 0 and half 1 stay independent with the same expectation, so the half-film error
// estimate (error_estimate.h) holds as before, with per-pixel weights n0 n1 / n^2.
//
// Why the image does not depend on the device split. The slots of a round are a function of the
// film at the round's start; slot k of a pixel draws samples 2^31 + (its half-1 count before the
// round) + k g onwards; passes take consecutive slots of the round's table, and in adaptive mode
// every pass size is a function of the image size alone (pass_schedule.cpp), so the passes, and
// with them the film's float sums, are the same on any devices, split and ranks.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "kernels/types.h"
#include "render/film.h"
#include "render/pass_schedule.h"

namespace clpt {

// The round a film is in (see above): ladder point `start_spp` to `end_spp`, and each half's
// samples per pixel at its end. `end_spp` <= the render's last sample count.
struct AdaptiveRound {
  uint64_t start_spp = 0;
  uint64_t end_spp = 0;
  uint64_t half1_end = 0;  // mean samples per pixel of half 1 at the round's end
  uint64_t half0_end = 0;  // half 0's (uniform)
  // The round's half-1 slots, P (half1_end - start_spp / 2) / g of them.
  uint64_t slot_total(uint64_t pixels, uint32_t granularity) const {
    return pixels * (half1_end - start_spp / 2) / granularity;
  }
};

// The round of `film` for a render that stops at `stop_spp` (kMaxSpp: no sample limit), or none
// while the film is below the ladder's first point (the uniform start) or at stop_spp.
std::optional<AdaptiveRound> adaptive_round(const Film& film, uint64_t stop_spp, uint32_t granularity);

// How many of `slot_total` slots each pixel gets: in proportion to the estimated standard deviation
// of a sample there, from half 0's per-sample variance over the pixel's eight neighbours (the pixel
// itself excluded, see above), capped at kAdaptiveWeightCap times the median so that one firefly
// in half 0 cannot draw a round's samples to a few pixels; rounded by largest remainders (ties to the
// lower pixel index), so the counts add up to slot_total exactly. Deterministic in the film's sums.
std::vector<uint32_t> adaptive_slot_counts(const Film& film, uint64_t slot_total);
// The weights before the cap: per pixel the square root of the mean of half 0's per-sample
// variance (mean over channels) over its neighbours with at least two samples (none: the image's
// mean variance).
std::vector<double> adaptive_weights(const Film& film);
constexpr double kAdaptiveWeightCap = 8.0;

// The round's slot table: pixel p's counts[p] slots, in pixel order.
// adaptive_pass_slots gives its slots [first, first + count) with their first sample indices
// (2^31 + the pixel's half-1 samples in `film` + g times the slot's rank among that pixel's slots
// in this pass); `film` must hold the table's first `first` slots already.
std::vector<GpuSampleSlot> adaptive_pass_slots(const Film& film, const std::vector<uint32_t>& counts, uint32_t granularity,
                                               uint64_t first, uint64_t count);

// The slots of a render's adaptive passes, as the coordinator computes them: each round's counts
// once (adaptive_slot_counts on the film at the round's start), each pass's slots from them.
class AdaptiveSlotTable {
 public:
  // The slots of `next` (an adaptive pass that plan_next_pass gave for `film` and `request`).
  // Throws std::logic_error when the film is in no round.
  std::vector<GpuSampleSlot> pass_slots(const Film& film, const NextPass& next, const PassRequest& request);

 private:
  std::vector<uint32_t> counts_;  // of the round that starts at round_start_
  uint64_t round_start_ = 0;
};

}  // namespace clpt
