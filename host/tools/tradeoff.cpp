#include "tools/tradeoff.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace clpt {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_same_shape(const MeanVarianceImage& render, const MeanVarianceImage& reference) {
  const size_t values = size_t(std::max(render.width, 0)) * size_t(std::max(render.height, 0)) * 3;
  if (render.width <= 0 || render.height <= 0 || render.width != reference.width ||
      render.height != reference.height || render.mean.size() != values || render.variance.size() != values ||
      reference.mean.size() != values || reference.variance.size() != values)
    throw std::invalid_argument("split_error: images of different or inconsistent sizes");
}

bool usable(const CurvePoint& p) {
  return std::isfinite(p.seconds) && std::isfinite(p.rmse) && p.seconds > 0 && p.rmse > 0;
}

bool is_all_digits(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

}  // namespace

std::string Combination::label() const {
  return std::string(precision_name(precision)) + "/" + estimator_name(estimator) + "/" +
         execution_form_name(form) + "/" + (sampler.empty() ? "" : sampler + "/") + (adaptive ? "adaptive/" : "") + "dev" +
         std::to_string(device_index);
}

ErrorSplit split_error(const MeanVarianceImage& render, const MeanVarianceImage& reference) {
  check_same_shape(render, reference);
  const size_t n = render.mean.size();
  double sum_sq = 0, sum_relative = 0, sum_var_render = 0, sum_var_reference = 0;
  // Welford mean and spread of e = (x - r)^2 - var_x - var_r, whose mean is MSE - noise.
  double e_mean = 0, e_m2 = 0;
  for (size_t i = 0; i < n; ++i) {
    const double d = double(render.mean[i]) - double(reference.mean[i]);
    const double r = reference.mean[i];
    const double var_x = render.variance[i], var_r = reference.variance[i];
    sum_sq += d * d;
    sum_relative += d * d / (r * r + kRelativeMseFloor);
    sum_var_render += var_x;
    sum_var_reference += var_r;
    const double e = d * d - var_x - var_r;
    const double delta = e - e_mean;
    e_mean += delta / double(i + 1);
    e_m2 += delta * (e - e_mean);
  }
  ErrorSplit s;
  s.mse = sum_sq / double(n);
  s.rmse = std::sqrt(s.mse);
  s.relative_mse = sum_relative / double(n);
  s.noise_render = sum_var_render / double(n);
  s.noise_reference = sum_var_reference / double(n);
  s.noise = s.noise_render + s.noise_reference;
  const double excess = s.mse - s.noise;
  s.bias_sq = std::isnan(excess) ? kNaN : std::max(0.0, excess);
  s.bias_sq_stderr = n > 1 ? std::sqrt(e_m2 / double(n - 1) / double(n)) : kNaN;
  s.bias_rms = std::sqrt(s.bias_sq);
  return s;
}

double noise_rms(const MeanVarianceImage& image) {
  if (image.variance.empty()) return kNaN;
  double sum = 0;
  for (float v : image.variance) sum += v;
  return std::sqrt(sum / double(image.variance.size()));
}

std::vector<double> geometric_budgets(double min_s, double max_s, int steps) {
  if (!(min_s > 0) || !(max_s >= min_s) || !std::isfinite(max_s))
    throw std::invalid_argument("the budgets need 0 < minimum <= maximum");
  if (steps < 1) throw std::invalid_argument("at least one budget is needed");
  if (steps == 1) {
    if (min_s != max_s) throw std::invalid_argument("one step needs the minimum equal to the maximum");
    return {min_s};
  }
  std::vector<double> budgets(static_cast<size_t>(steps));
  const double ratio = max_s / min_s;
  for (int i = 0; i < steps; ++i) budgets[size_t(i)] = min_s * std::pow(ratio, double(i) / double(steps - 1));
  budgets.front() = min_s;  // exact ends, whatever pow rounds to
  budgets.back() = max_s;
  return budgets;
}

std::vector<CurvePoint> curve_of(const std::vector<TradeoffRun>& runs, const std::string& label) {
  std::vector<CurvePoint> curve;
  for (const TradeoffRun& run : runs)
    if (run.budget_s > 0 && run.combination.label() == label) curve.push_back({run.render_s, run.error.rmse});
  std::sort(curve.begin(), curve.end(),
            [](const CurvePoint& a, const CurvePoint& b) { return a.seconds < b.seconds; });
  return curve;
}

TimeToError time_to_reach(const std::vector<CurvePoint>& curve, double target_rmse) {
  std::vector<CurvePoint> points;
  for (const CurvePoint& p : curve)
    if (usable(p)) points.push_back(p);
  std::sort(points.begin(), points.end(),
            [](const CurvePoint& a, const CurvePoint& b) { return a.seconds < b.seconds; });
  if (points.empty() || !(target_rmse > 0) || !std::isfinite(target_rmse)) return {Reach::NotReached, 0};
  if (points.front().rmse <= target_rmse) return {Reach::AtOrBeforeFirst, points.front().seconds};
  for (size_t i = 1; i < points.size(); ++i) {
    if (points[i].rmse > target_rmse) continue;
    const CurvePoint& a = points[i - 1];  // above the target
    const CurvePoint& b = points[i];      // at or below it, so log(b.rmse) < log(a.rmse)
    const double fraction = (std::log(target_rmse) - std::log(a.rmse)) / (std::log(b.rmse) - std::log(a.rmse));
    return {Reach::Interpolated, std::exp(std::log(a.seconds) + fraction * (std::log(b.seconds) - std::log(a.seconds)))};
  }
  return {Reach::NotReached, 0};
}

double rmse_stderr(const ErrorSplit& error) {
  const double se = error.bias_sq_stderr / (2 * error.rmse);
  return std::isfinite(se) && se > 0 ? se : 0;
}

std::vector<std::string> dominated_by(const std::vector<TradeoffRun>& runs, const std::string& label) {
  // Budget -> run of `label`.
  std::vector<const TradeoffRun*> own;
  for (const TradeoffRun& r : runs)
    if (r.budget_s > 0 && r.combination.label() == label) own.push_back(&r);
  std::vector<std::string> out;
  if (own.empty()) return out;
  std::vector<std::string> others;
  for (const TradeoffRun& r : runs) {
    const std::string other = r.combination.label();
    if (r.budget_s > 0 && other != label && std::find(others.begin(), others.end(), other) == others.end())
      others.push_back(other);
  }
  for (const std::string& other : others) {
    int common = 0;
    bool never_worse = true, once_clearly_better = false;
    for (const TradeoffRun* a : own)
      for (const TradeoffRun& b : runs) {
        if (b.budget_s != a->budget_s || b.combination.label() != other) continue;
        ++common;
        const bool finite = std::isfinite(b.error.rmse) && std::isfinite(a->error.rmse);
        if (!finite || b.render_s > a->render_s * (1 + kDominanceTimeSlack) || b.error.rmse > a->error.rmse)
          never_worse = false;
        const double noise = std::hypot(rmse_stderr(a->error), rmse_stderr(b.error));
        const double gain = a->error.rmse - b.error.rmse;
        if (finite && gain >= kDominanceMargin * a->error.rmse && gain > kDominanceSigmas * noise)
          once_clearly_better = true;
      }
    if (common > 0 && never_worse && once_clearly_better) out.push_back(other);
  }
  return out;
}

Combination TargetFrom::applied_to(const Combination& first) const {
  Combination c = first;
  if (precision) c.precision = *precision;
  if (estimator) c.estimator = *estimator;
  if (form) c.form = *form;
  return c;
}

TargetFrom parse_target_from(const std::string& text) {
  const size_t at = text.rfind('@');
  if (at == std::string::npos)
    throw std::invalid_argument("expected NAMES@SPP, e.g. book@256 or double/book@1024");
  const std::string spp_text = text.substr(at + 1);
  TargetFrom t;
  if (!is_all_digits(spp_text) || spp_text.size() > 10 || std::stoull(spp_text) == 0 ||
      std::stoull(spp_text) > (uint64_t(1) << 31))
    throw std::invalid_argument("'" + spp_text + "' is not a sample count in 1..2147483648");
  t.spp = std::stoull(spp_text);
  std::istringstream names(text.substr(0, at));
  for (std::string name; std::getline(names, name, '/');) {
    bool duplicate = false;
    if (auto p = parse_precision(name)) {
      duplicate = t.precision.has_value();
      t.precision = p;
    } else if (auto e = parse_estimator(name)) {
      duplicate = t.estimator.has_value();
      t.estimator = e;
    } else if (name == "megakernel" || name == "wavefront") {
      duplicate = t.form.has_value();
      t.form = name == "wavefront" ? ExecutionForm::Wavefront : ExecutionForm::Megakernel;
    } else {
      throw std::invalid_argument("'" + name + "' is not a precision (fast, robust, double), an estimator "
                                  "(book, nee) or a form (megakernel, wavefront)");
    }
    if (duplicate) throw std::invalid_argument("'" + name + "': two values of the same kind");
  }
  return t;
}

}  // namespace clpt
