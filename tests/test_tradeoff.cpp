// `clpt tradeoff`'s pure parts (tools/tradeoff.h, tools/tradeoff_output.h), without a device:
// the noise/bias split on synthetic images whose bias and variance are known, budgets, the
// time-to-error interpolation, --target-from parsing, and the CSV/JSON/gnuplot text.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "tools/tradeoff.h"
#include "tools/tradeoff_output.h"

namespace clpt {
namespace {

constexpr int kWidth = 64, kHeight = 64;
constexpr size_t kValues = size_t(kWidth) * kHeight * 3;

double true_value(size_t i) { return 0.05 + 0.9 * double(i % 97) / 97.0; }
// Variance of the mean that differs from pixel to pixel, as in a render.
double true_variance(size_t i, double scale) { return scale * (0.5 + double(i % 13) / 13.0); }

// The reference: true values plus normal noise of the stated variance, which its variance
// channel carries exactly.
MeanVarianceImage noisy_image(uint32_t seed, double bias, double variance_scale) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  MeanVarianceImage img{kWidth, kHeight, std::vector<float>(kValues), std::vector<float>(kValues)};
  for (size_t i = 0; i < kValues; ++i) {
    const double v = true_variance(i, variance_scale);
    img.mean[i] = float(true_value(i) + bias + std::sqrt(v) * normal(rng));
    img.variance[i] = float(v);
  }
  return img;
}

// The standard error of mean((x - r)^2 - var) when the variances are exact: d ~ N(b, s^2) has
// Var(d^2) = 2 s^4 + 4 b^2 s^2.
double theoretical_bias_sq_stderr(double bias, double render_scale, double reference_scale) {
  double sum = 0;
  for (size_t i = 0; i < kValues; ++i) {
    const double s2 = true_variance(i, render_scale) + true_variance(i, reference_scale);
    sum += 2 * s2 * s2 + 4 * bias * bias * s2;
  }
  return std::sqrt(sum) / double(kValues);
}

TEST(TradeoffErrorSplit, RecoversAKnownBiasAndTheNoise) {
  const double bias = 0.03, render_scale = 4e-3, reference_scale = 1e-3;
  const MeanVarianceImage reference = noisy_image(1, 0.0, reference_scale);
  const MeanVarianceImage render = noisy_image(2, bias, render_scale);
  const ErrorSplit s = split_error(render, reference);
  const double stderr_theory = theoretical_bias_sq_stderr(bias, render_scale, reference_scale);
  // The variance channels are exact here, so the noise terms are their means.
  double mean_render = 0, mean_reference = 0;
  for (size_t i = 0; i < kValues; ++i) mean_render += render.variance[i], mean_reference += reference.variance[i];
  EXPECT_NEAR(s.noise_render, mean_render / kValues, 1e-9);
  EXPECT_NEAR(s.noise_reference, mean_reference / kValues, 1e-9);
  EXPECT_DOUBLE_EQ(s.noise, s.noise_render + s.noise_reference);
  EXPECT_NEAR(s.bias_sq, bias * bias, 4 * stderr_theory);
  EXPECT_NEAR(s.bias_sq_stderr, stderr_theory, 0.1 * stderr_theory);
  EXPECT_DOUBLE_EQ(s.bias_rms, std::sqrt(s.bias_sq));
  EXPECT_DOUBLE_EQ(s.rmse, std::sqrt(s.mse));
  // The bias is far outside the noise of its estimate: the split must say it is real.
  EXPECT_GT(s.bias_sq, 10 * s.bias_sq_stderr);
}

TEST(TradeoffErrorSplit, UnbiasedRenderShowsNoSignificantBias) {
  const double render_scale = 4e-3, reference_scale = 1e-3;
  const ErrorSplit s = split_error(noisy_image(3, 0.0, render_scale), noisy_image(4, 0.0, reference_scale));
  const double stderr_theory = theoretical_bias_sq_stderr(0.0, render_scale, reference_scale);
  EXPECT_LE(s.bias_sq, 4 * stderr_theory);
  EXPECT_NEAR(s.mse, s.noise, 4 * stderr_theory);
}

// As in a film: each pixel channel the mean of n skewed samples and the variance of that mean
// estimated from the same samples (s^2 / n). The estimate is unbiased, so no bias may appear.
TEST(TradeoffErrorSplit, EstimatedVariancesOfSkewedSamplesShowNoBias) {
  std::mt19937 rng(5);
  std::exponential_distribution<double> sample(1.0);
  auto film_like = [&](int n) {
    MeanVarianceImage img{kWidth, kHeight, std::vector<float>(kValues), std::vector<float>(kValues)};
    for (size_t i = 0; i < kValues; ++i) {
      double sum = 0, sum_sq = 0;
      for (int k = 0; k < n; ++k) {
        const double x = true_value(i) * sample(rng);  // mean true_value(i)
        sum += x, sum_sq += x * x;
      }
      const double mean = sum / n;
      img.mean[i] = float(mean);
      img.variance[i] = float((sum_sq - n * mean * mean) / (n - 1) / n);
    }
    return img;
  };
  const MeanVarianceImage reference = film_like(64), render = film_like(8);
  const ErrorSplit s = split_error(render, reference);
  EXPECT_LE(s.mse - s.noise, 4 * s.bias_sq_stderr);
  EXPECT_GE(s.mse - s.noise, -4 * s.bias_sq_stderr);
}

TEST(TradeoffErrorSplit, RelativeMseUsesTheStatedFloor) {
  MeanVarianceImage reference{1, 1, {1, 1, 0}, {0, 0, 0}};
  MeanVarianceImage render{1, 1, {1, 2, 0.5f}, {0, 0, 0}};
  const ErrorSplit s = split_error(render, reference);
  const double expected = (0 + 1 / (1 + kRelativeMseFloor) + 0.25 / (0 + kRelativeMseFloor)) / 3;
  EXPECT_NEAR(s.relative_mse, expected, 1e-12);
  EXPECT_NEAR(s.mse, 1.25 / 3, 1e-12);
  EXPECT_DOUBLE_EQ(s.noise, 0.0);
  EXPECT_NEAR(s.bias_sq, s.mse, 1e-15);
}

TEST(TradeoffErrorSplit, NoiseAboveTheErrorClampsBiasToZero) {
  MeanVarianceImage reference{1, 1, {1, 1, 1}, {1, 1, 1}};
  MeanVarianceImage render{1, 1, {1.1f, 1, 1}, {1, 1, 1}};
  const ErrorSplit s = split_error(render, reference);
  EXPECT_EQ(s.bias_sq, 0.0);
  EXPECT_EQ(s.bias_rms, 0.0);
}

TEST(TradeoffErrorSplit, RejectsDifferentSizesAndPropagatesNaN) {
  MeanVarianceImage a{1, 1, {1, 1, 1}, {0, 0, 0}};
  MeanVarianceImage b{2, 1, {1, 1, 1, 1, 1, 1}, {0, 0, 0, 0, 0, 0}};
  EXPECT_THROW(split_error(a, b), std::invalid_argument);
  MeanVarianceImage nan = a;
  nan.mean[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(split_error(nan, a).rmse));
  EXPECT_TRUE(std::isnan(split_error(nan, a).bias_sq));
}

TEST(TradeoffNoise, RmsOfTheStandardError) {
  MeanVarianceImage img{1, 2, std::vector<float>(6, 1), {0.01f, 0.01f, 0.01f, 0.04f, 0.04f, 0.04f}};
  EXPECT_NEAR(noise_rms(img), std::sqrt(0.025), 1e-7);
}

TEST(TradeoffBudgets, GeometricWithExactEnds) {
  const std::vector<double> b = geometric_budgets(0.25, 2, 4);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_EQ(b.front(), 0.25);
  EXPECT_EQ(b.back(), 2.0);
  for (size_t i = 1; i < b.size(); ++i) EXPECT_NEAR(b[i] / b[i - 1], 2.0, 1e-12);
  const std::vector<double> c = geometric_budgets(0.1, 10, 5);
  for (size_t i = 1; i < c.size(); ++i) EXPECT_NEAR(c[i] / c[i - 1], std::sqrt(10.0), 1e-12);
  EXPECT_EQ(geometric_budgets(3, 3, 1), std::vector<double>{3});
}

TEST(TradeoffBudgets, RejectsBadRanges) {
  EXPECT_THROW(geometric_budgets(0, 1, 3), std::invalid_argument);
  EXPECT_THROW(geometric_budgets(-1, 1, 3), std::invalid_argument);
  EXPECT_THROW(geometric_budgets(2, 1, 3), std::invalid_argument);
  EXPECT_THROW(geometric_budgets(1, 2, 1), std::invalid_argument);
  EXPECT_THROW(geometric_budgets(1, 2, 0), std::invalid_argument);
  EXPECT_THROW(geometric_budgets(1, std::numeric_limits<double>::infinity(), 3), std::invalid_argument);
}

// RMSE of an unbiased estimator: c / sqrt(t), a straight line in log-log axes, so the
// interpolation must be exact on it.
std::vector<CurvePoint> power_law_curve() {
  std::vector<CurvePoint> curve;
  for (double t : {1.0, 2.0, 4.0, 8.0}) curve.push_back({t, 0.1 / std::sqrt(t)});
  return curve;
}

TEST(TradeoffTimeToError, ExactOnAPowerLaw) {
  const TimeToError t = time_to_reach(power_law_curve(), 0.1 / std::sqrt(3.0));
  EXPECT_EQ(t.reach, Reach::Interpolated);
  EXPECT_NEAR(t.seconds, 3.0, 1e-12);
  const TimeToError at_point = time_to_reach(power_law_curve(), 0.1 / std::sqrt(4.0));
  EXPECT_EQ(at_point.reach, Reach::Interpolated);
  EXPECT_NEAR(at_point.seconds, 4.0, 1e-12);
}

TEST(TradeoffTimeToError, NoExtrapolation) {
  const TimeToError early = time_to_reach(power_law_curve(), 0.2);
  EXPECT_EQ(early.reach, Reach::AtOrBeforeFirst);
  EXPECT_EQ(early.seconds, 1.0);
  EXPECT_EQ(time_to_reach(power_law_curve(), 0.01).reach, Reach::NotReached);
  EXPECT_EQ(time_to_reach({}, 0.1).reach, Reach::NotReached);
  EXPECT_EQ(time_to_reach(power_law_curve(), 0).reach, Reach::NotReached);
}

TEST(TradeoffTimeToError, UnsortedNoisyAndInvalidPoints) {
  // Order does not matter; the first crossing in time counts even if a later point rises again;
  // points with zero or non-finite values are skipped.
  std::vector<CurvePoint> curve = {{4, 0.04}, {1, 0.1}, {2, 0.08}, {8, 0.06}, {0, 0.01},
                                   {3, std::numeric_limits<double>::quiet_NaN()}};
  const TimeToError t = time_to_reach(curve, 0.05);
  EXPECT_EQ(t.reach, Reach::Interpolated);
  const double fraction = std::log(0.05 / 0.08) / std::log(0.04 / 0.08);
  EXPECT_NEAR(t.seconds, std::exp(std::log(2.0) + fraction * std::log(2.0)), 1e-12);
}

Combination combination(ExecutionForm form, const std::string& device_name = "cpu") {
  Combination c;
  c.form = form;
  c.device_name = device_name;
  return c;
}

TradeoffRun budget_run(const Combination& c, double budget, double seconds, double rmse, uint64_t spp = 16) {
  TradeoffRun r;
  r.combination = c;
  r.budget_s = budget;
  r.render_s = seconds;
  r.spp = spp;
  r.paths = spp * 100;
  r.error.rmse = rmse;
  r.error.mse = rmse * rmse;
  return r;
}

TEST(TradeoffCurve, OneCombinationsBudgetRunsByTime) {
  const Combination mega = combination(ExecutionForm::Megakernel), wave = combination(ExecutionForm::Wavefront);
  TradeoffRun fixed = budget_run(mega, 0, 0.5, 0.01);
  fixed.fixed_spp = 256;
  const std::vector<TradeoffRun> runs = {budget_run(mega, 2, 2.1, 0.05), budget_run(wave, 1, 1.0, 0.07),
                                         budget_run(mega, 1, 1.05, 0.07), fixed};
  const std::vector<CurvePoint> curve = curve_of(runs, mega.label());
  ASSERT_EQ(curve.size(), 2u);
  EXPECT_EQ(curve[0].seconds, 1.05);
  EXPECT_EQ(curve[1].seconds, 2.1);
  EXPECT_EQ(mega.label(), "robust/book/megakernel/dev0");
}

// --sampler with several samplers makes the sampler a dimension: its own curve and label.
TEST(TradeoffCurve, SeveralSamplersAreSeparateCurves) {
  Combination jitter = combination(ExecutionForm::Megakernel), sobol = jitter;
  jitter.sampler = "jitter";
  sobol.sampler = "sobol";
  EXPECT_EQ(sobol.label(), "robust/book/megakernel/sobol/dev0");
  const std::vector<TradeoffRun> runs = {budget_run(jitter, 1, 1.0, 0.07), budget_run(sobol, 1, 1.1, 0.04),
                                         budget_run(sobol, 2, 2.2, 0.02)};
  EXPECT_EQ(curve_of(runs, jitter.label()).size(), 1u);
  const std::vector<CurvePoint> curve = curve_of(runs, sobol.label());
  ASSERT_EQ(curve.size(), 2u);
  EXPECT_EQ(curve[1].rmse, 0.02);
}

// --adaptive off,on makes adaptive sampling a dimension, with its own label.
TEST(TradeoffCurve, AdaptiveSamplingIsItsOwnCurve) {
  Combination plain = combination(ExecutionForm::Megakernel), adaptive = plain;
  adaptive.adaptive = true;
  EXPECT_EQ(adaptive.label(), "robust/book/megakernel/adaptive/dev0");
  adaptive.sampler = "sobol";
  EXPECT_EQ(adaptive.label(), "robust/book/megakernel/sobol/adaptive/dev0");
  const std::vector<TradeoffRun> runs = {budget_run(plain, 1, 1.0, 0.07), budget_run(adaptive, 1, 1.1, 0.04)};
  EXPECT_EQ(curve_of(runs, plain.label()).size(), 1u);
  EXPECT_EQ(curve_of(runs, adaptive.label()).size(), 1u);
}

TEST(TradeoffTargetFrom, ParsesNamesInAnyOrder) {
  const TargetFrom a = parse_target_from("book@256");
  EXPECT_EQ(a.spp, 256u);
  EXPECT_EQ(a.estimator, Estimator::Book);
  EXPECT_FALSE(a.precision.has_value());
  EXPECT_FALSE(a.form.has_value());
  const TargetFrom b = parse_target_from("wavefront/double/nee@1024");
  EXPECT_EQ(b.precision, Precision::Double);
  EXPECT_EQ(b.estimator, Estimator::Nee);
  EXPECT_EQ(b.form, ExecutionForm::Wavefront);
  const Combination first = combination(ExecutionForm::Megakernel);
  const Combination applied = b.applied_to(first);
  EXPECT_EQ(applied.label(), "double/nee/wavefront/dev0");
  EXPECT_EQ(parse_target_from("@16").applied_to(first).label(), first.label());
}

TEST(TradeoffTargetFrom, RejectsMalformedSpecs) {
  for (const char* bad : {"book", "book@", "book@0", "book@x", "book@-1", "book@99999999999", "frobnicate@16",
                          "book/nee@16", "book//robust@16"})
    EXPECT_THROW(parse_target_from(bad), std::invalid_argument) << bad;
}

TEST(TradeoffCsv, EscapesFields) {
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csv_field("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csv_field(""), "");
}

// Splits one CSV record (RFC 4180 quoting, no embedded newlines needed here).
std::vector<std::string> parse_csv_line(const std::string& line) {
  std::vector<std::string> fields(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') fields.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) fields.emplace_back();
    else fields.back() += c;
  }
  return fields;
}

TEST(TradeoffCsv, OneRowPerRunWithAwkwardDeviceNames) {
  const Combination c = combination(ExecutionForm::Wavefront, "gpu, \"fast\" one");
  TradeoffRun one_sample = budget_run(c, 0.25, 0.26, 0.3, 1);
  one_sample.error.bias_sq = 0.5;  // must not be printed: unknown below 2 spp
  const std::string csv = tradeoff_csv({budget_run(c, 0.5, 0.51, 0.2), one_sample});
  std::istringstream lines(csv);
  std::string header, row1, row2, extra;
  std::getline(lines, header);
  std::getline(lines, row1);
  std::getline(lines, row2);
  EXPECT_FALSE(std::getline(lines, extra));
  const std::vector<std::string> names = parse_csv_line(header);
  ASSERT_EQ(names.size(), 22u);
  EXPECT_EQ(names[0], "run");
  EXPECT_EQ(names[12], "rmse");
  for (const std::string& row : {row1, row2}) {
    const std::vector<std::string> fields = parse_csv_line(row);
    ASSERT_EQ(fields.size(), names.size()) << row;
    EXPECT_EQ(fields[5], "gpu, \"fast\" one");
  }
  const std::vector<std::string> second = parse_csv_line(row2);
  EXPECT_EQ(second[18], "");  // bias_sq unknown at 1 spp
  EXPECT_EQ(std::stod(second[12]), 0.3);
}

TradeoffResult two_curve_result() {
  const Combination mega = combination(ExecutionForm::Megakernel), wave = combination(ExecutionForm::Wavefront);
  TradeoffResult r;
  r.scene = "scenes/diffuse.toml";
  r.reference = {"it's.exr", 32, 24, 256, 0.01};
  r.combinations = {mega, wave};
  r.runs = {budget_run(mega, 1, 1, 0.1), budget_run(mega, 2, 2, 0.07), budget_run(wave, 1, 1, 0.05),
            budget_run(wave, 2, 2, 0.035)};
  r.targets = {{0.06, "--target-rmse"}};
  return r;
}

TEST(TradeoffJson, FiguresAndTimesToReach) {
  const nlohmann::json j = nlohmann::json::parse(tradeoff_json(two_curve_result()));
  EXPECT_EQ(j["runs"].size(), 4u);
  EXPECT_EQ(j["reference"]["spp"], 256);
  EXPECT_TRUE(j["runs"][0]["fixed_spp"].is_null());
  const nlohmann::json& times = j["targets"][0]["time_to_reach"];
  ASSERT_EQ(times.size(), 2u);
  EXPECT_EQ(times[0]["status"], "not_reached");
  EXPECT_TRUE(times[0]["seconds"].is_null());
  EXPECT_EQ(times[1]["status"], "at_or_before_smallest_budget");
  EXPECT_EQ(times[1]["seconds"], 1.0);
}

TEST(TradeoffTable, SaysNotReachedAndAtOrBefore) {
  const std::string table = time_to_error_table(two_curve_result());
  EXPECT_NE(table.find("robust/book/megakernel/dev0  not reached"), std::string::npos) << table;
  EXPECT_NE(table.find("robust/book/wavefront/dev0   <= 1 s"), std::string::npos) << table;
}

TEST(TradeoffGnuplot, OneDataBlockPerCurveAndQuotedStrings) {
  const std::string script = gnuplot_script(two_curve_result(), "/tmp/it's.png");
  EXPECT_NE(script.find("set output '/tmp/it''s.png'"), std::string::npos) << script;
  EXPECT_NE(script.find("set logscale xy"), std::string::npos);
  EXPECT_NE(script.find("$c0 << EOD\n1 0.1\n2 0.07\nEOD\n"), std::string::npos) << script;
  EXPECT_NE(script.find("$c1 << EOD\n1 0.05\n2 0.035\nEOD\n"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'robust/book/wavefront/dev0'"), std::string::npos);
  EXPECT_NE(script.find("first 0.06"), std::string::npos);  // the target line
}

// dominated_by: beaten at every common budget in RMSE, clearly at one, and in no more time.
TEST(TradeoffDominance, LowerCurveInNoMoreTimeDominates) {
  const Combination mega = combination(ExecutionForm::Megakernel), wave = combination(ExecutionForm::Wavefront);
  const TradeoffResult r = two_curve_result();
  EXPECT_EQ(dominated_by(r.runs, mega.label()), std::vector<std::string>{wave.label()});
  EXPECT_TRUE(dominated_by(r.runs, wave.label()).empty());
  EXPECT_TRUE(dominated_by(r.runs, "no/such/combination").empty());
}

TEST(TradeoffDominance, CrossingCurvesNoiseAndSlowerRunsDoNotDominate) {
  const Combination a = combination(ExecutionForm::Megakernel), b = combination(ExecutionForm::Wavefront);
  // The curves cross: b is lower at 1 s, higher at 2 s.
  const std::vector<TradeoffRun> crossing = {budget_run(a, 1, 1, 0.1), budget_run(a, 2, 2, 0.05),
                                             budget_run(b, 1, 1, 0.08), budget_run(b, 2, 2, 0.06)};
  EXPECT_TRUE(dominated_by(crossing, a.label()).empty());
  EXPECT_TRUE(dominated_by(crossing, b.label()).empty());
  // b lower everywhere, but by less than kDominanceMargin: within the curves' own spread.
  const std::vector<TradeoffRun> close = {budget_run(a, 1, 1, 0.1), budget_run(b, 1, 1, 0.097)};
  EXPECT_TRUE(dominated_by(close, a.label()).empty());
  // b 20% lower, but each image's own spread gives its RMSE a standard error of 0.008 (se(MSE) /
  // (2 RMSE)): 0.02 is under twice the combined 0.0113, a difference within noise.
  std::vector<TradeoffRun> noisy = {budget_run(a, 1, 1, 0.1), budget_run(b, 1, 1, 0.08)};
  for (TradeoffRun& run : noisy) run.error.bias_sq_stderr = 2 * run.error.rmse * 0.008;
  EXPECT_NEAR(rmse_stderr(noisy[0].error), 0.008, 1e-12);
  EXPECT_TRUE(dominated_by(noisy, a.label()).empty());
  // The same 20% with standard errors of 0.004 (combined 0.0057, twice that 0.0113): clearly lower.
  for (TradeoffRun& run : noisy) run.error.bias_sq_stderr = 2 * run.error.rmse * 0.004;
  EXPECT_EQ(dominated_by(noisy, a.label()), std::vector<std::string>{b.label()});
  // b lower, but its run took more than kDominanceTimeSlack longer.
  const std::vector<TradeoffRun> slower = {budget_run(a, 1, 1, 0.1), budget_run(b, 1, 1.2, 0.05)};
  EXPECT_TRUE(dominated_by(slower, a.label()).empty());
  // Within the slack it is the same time.
  const std::vector<TradeoffRun> same_time = {budget_run(a, 1, 1, 0.1), budget_run(b, 1, 1.05, 0.05)};
  EXPECT_EQ(dominated_by(same_time, a.label()), std::vector<std::string>{b.label()});
  // No budget in common, and fixed-spp runs: nothing to compare.
  TradeoffRun fixed = budget_run(b, 0, 0.5, 0.01);
  fixed.fixed_spp = 256;
  const std::vector<TradeoffRun> apart = {budget_run(a, 1, 1, 0.1), budget_run(b, 2, 1, 0.01), fixed};
  EXPECT_TRUE(dominated_by(apart, a.label()).empty());
}

TEST(TradeoffDominance, InTheTableTheJsonAndThePlot) {
  const TradeoffResult r = two_curve_result();
  const std::string table = time_to_error_table(r);
  EXPECT_NE(table.find("robust/book/megakernel/dev0: dominated by robust/book/wavefront/dev0"), std::string::npos)
      << table;
  const nlohmann::json j = nlohmann::json::parse(tradeoff_json(r));
  ASSERT_EQ(j["combinations"].size(), 2u);
  EXPECT_EQ(j["combinations"][0]["dominated_by"], nlohmann::json::array({"robust/book/wavefront/dev0"}));
  EXPECT_EQ(j["combinations"][1]["dominated_by"], nlohmann::json::array());
  const std::string script = gnuplot_script(r, "/tmp/x.png");
  EXPECT_NE(script.find("dt 2 title 'robust/book/megakernel/dev0 (dominated)'"), std::string::npos) << script;
  TradeoffResult none = r;
  none.runs = {budget_run(combination(ExecutionForm::Megakernel), 1, 1, 0.1)};
  EXPECT_NE(time_to_error_table(none).find("no combination is beaten"), std::string::npos);
}

}  // namespace
}  // namespace clpt
