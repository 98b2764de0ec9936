// The measurements of `clpt tradeoff`: how the error of a render against a reference falls with
// render time, for each combination of precision, estimator, execution form, sampler and device. Pure
// functions (no device, no files), so tests run them on synthetic images.
//
// Error model. x is a render's pixel-channel mean, r the reference's, both independent
// estimates: E[(x - r)^2] = bias^2 + Var(x) + Var(r), with bias = E[x] - E[r]. Each film carries
// its own variance of the mean per pixel channel (Film::variance_rgb, the EXR's variance.*
// channels), so the mean squared error over the image splits into
//   noise  = mean over pixels and channels of (var_x + var_r): what MSE would be without bias
//   bias^2 = max(0, MSE - noise)
// bias^2 is a difference of two estimates and has its own standard error, reported beside it: a
// bias^2 within about two standard errors of 0 is indistinguishable from none.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "kernels/kernel_options.h"
#include "render/renderer.h"
#include "tools/image_compare.h"

namespace clpt {

// One curve of the plot: what is varied by `clpt tradeoff`.
struct Combination {
  Precision precision = Precision::Robust;
  Estimator estimator = Estimator::Book;
  ExecutionForm form = ExecutionForm::Megakernel;
  std::string device_spec;  // as given to --device ("" = the default device)
  int device_index = 0;     // in `clpt devices`
  std::string device_name;
  // --sampler with several samplers: this one's name ("jitter", "grid", "sobol"); empty: the
  // scene's sampler, which is then not part of the label.
  std::string sampler;
  bool adaptive = false;  // --adaptive on: adaptive sampling (render/adaptive_sampling.h)
  // "robust/book/megakernel/dev0" (with several samplers "robust/book/megakernel/sobol/dev0";
  // adaptive: ".../adaptive/dev0"): unique per combination, used in tables, CSV and the plot.
  std::string label() const;
};

// Relative MSE is mean((x - r)^2 / (r^2 + kRelativeMseFloor)): the floor keeps black pixels of
// the reference from dominating it.
constexpr double kRelativeMseFloor = 1e-2;

struct ErrorSplit {
  double mse = 0;              // mean over pixels and channels of (x - r)^2
  double rmse = 0;             // sqrt(mse)
  double relative_mse = 0;     // mean of (x - r)^2 / (r^2 + kRelativeMseFloor)
  double noise_render = 0;     // mean of the render's variance of the pixel mean
  double noise_reference = 0;  // mean of the reference's variance of the pixel mean
  double noise = 0;            // noise_render + noise_reference: MSE expected without bias
  double bias_sq = 0;          // max(0, mse - noise)
  double bias_sq_stderr = 0;   // standard error of mse - noise (pixel channels independent)
  double bias_rms = 0;         // sqrt(bias_sq)
};

// Contract: same width and height, 3 floats a pixel in mean and variance (throws
// std::invalid_argument otherwise). NaN anywhere makes the figures NaN.
ErrorSplit split_error(const MeanVarianceImage& render, const MeanVarianceImage& reference);

// RMS over pixels and channels of the standard error of the pixel means: sqrt(mean(variance)).
double noise_rms(const MeanVarianceImage& image);

// `steps` budgets from min_s to max_s in geometric progression (both included). Throws
// std::invalid_argument unless 0 < min_s <= max_s, steps >= 1, and steps == 1 only when
// min_s == max_s.
std::vector<double> geometric_budgets(double min_s, double max_s, int steps);

// One render of `clpt tradeoff`: a time budget, or a fixed sample count for a --target-from run.
struct TradeoffRun {
  Combination combination;
  double budget_s = 0;      // > 0: rendered for this long; 0: a fixed-spp run
  uint64_t fixed_spp = 0;   // > 0 for a --target-from run
  double render_s = 0;      // measured time of the passes (kernel build excluded)
  double build_s = 0;       // kernel build of this run (from clpt's cache after the warm-up)
  uint64_t spp = 0;
  uint64_t paths = 0;
  uint64_t dropped = 0;     // NaN/Inf samples excluded from the film
  ErrorSplit error;
  double paths_per_s() const { return render_s > 0 ? double(paths) / render_s : 0; }
  // The film's variance needs two samples a pixel; below that noise and bias are unknown.
  bool noise_known() const { return spp >= 2; }
};

// (measured render time, RMSE) of a combination's budget runs, ordered by time.
struct CurvePoint {
  double seconds = 0;
  double rmse = 0;
};
std::vector<CurvePoint> curve_of(const std::vector<TradeoffRun>& runs, const std::string& label);

enum class Reach {
  Interpolated,      // crossed between two measured points
  AtOrBeforeFirst,   // already at or below the target at the first (smallest) point
  NotReached,        // above the target at every point
};

struct TimeToError {
  Reach reach = Reach::NotReached;
  double seconds = 0;  // Interpolated: the time; AtOrBeforeFirst: the first point's time
};

// When the curve first reaches `target_rmse`, interpolating log RMSE linearly in log time between
// the last point above the target and the first at or below it. Points with non-positive or
// non-finite values are ignored. No extrapolation on either side.
TimeToError time_to_reach(const std::vector<CurvePoint>& curve, double target_rmse);

// Which combinations beat `label` in both time and error. B dominates A when they ran at least
// one time budget in common and at every common budget B's run took no longer than A's (within
// kDominanceTimeSlack: a budget is a time limit, so runs of one budget end a little apart) and
// reached an RMSE no higher, and at one budget at least an RMSE clearly lower: by more than
// kDominanceSigmas combined standard errors of the two RMSEs (rmse_stderr, from each image's own
// spread of squared errors), and by kDominanceMargin at least, a floor for what a user would call
// better and for the error of the runs' timing, which no image measures. A dominated combination
// is never the one to pick: B gives a better image in the same time. Fixed-spp runs (budget 0)
// are not compared. Labels in the order of first appearance in `runs`.
constexpr double kDominanceTimeSlack = 0.10;  // B's render time <= 1.10 x A's
constexpr double kDominanceSigmas = 2.0;      // B's RMSE lower by > 2 combined standard errors...
constexpr double kDominanceMargin = 0.05;     // ...and by >= 5% of A's, at one budget at least
// Standard error of a run's RMSE, from the standard error of its mean squared error (the pixel
// channels' spread, ErrorSplit::bias_sq_stderr): se(MSE) / (2 RMSE), the first-order propagation
// through the square root. 0 when unknown (fewer than two pixel channels, or an RMSE of 0).
double rmse_stderr(const ErrorSplit& error);
std::vector<std::string> dominated_by(const std::vector<TradeoffRun>& runs, const std::string& label);

// An RMSE to reach, and where it came from (for the table).
struct ErrorTarget {
  double rmse = 0;
  std::string source;  // "--target-rmse", "robust/book/megakernel/dev0 at 256 spp", ...
};

// `--target-from [PRECISION/][ESTIMATOR/][FORM/]...@SPP`: '/'-separated names, each a
// precision, estimator or form (their names are disjoint), in any order; what is not named is
// taken from the first combination. Throws std::invalid_argument with a message naming the part.
struct TargetFrom {
  std::optional<Precision> precision;
  std::optional<Estimator> estimator;
  std::optional<ExecutionForm> form;
  uint64_t spp = 0;
  Combination applied_to(const Combination& first) const;
};
TargetFrom parse_target_from(const std::string& text);

}  // namespace clpt
