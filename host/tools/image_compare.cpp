#include "tools/image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "util/appendf.h"

namespace clpt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Zero-variance values (e.g. black background, or 1-sample pixels) must agree this closely.
constexpr double kZeroVarianceRelative = 1e-6;
const char* const kChannelNames[3] = {"R", "G", "B"};

// |a - b| <= relative * max(|a|, |b|, 1e-6); false when either is NaN.
bool agree_within(double a, double b, double relative) {
  return std::abs(a - b) <= relative * std::max({std::abs(a), std::abs(b), 1e-6});
}

// Welch z of a - b given the variance of that difference. Zero variance: 0 when a and b agree,
// else +-infinity (a certain difference). NaN in, NaN out.
double welch_z(double a, double b, double variance) {
  const double diff = a - b;
  if (std::isnan(diff) || std::isnan(variance)) return kNaN;
  if (variance > 0) return diff / std::sqrt(variance);
  if (agree_within(a, b, kZeroVarianceRelative)) return 0.0;
  return diff > 0 ? kInf : -kInf;
}

// A test at level alpha accepts when the p-value exceeds alpha; NaN never accepts.
bool accepts(double z, double alpha) { return two_sided_p_value(z) > alpha; }

void check_same_shape(const MeanVarianceImage& a, const MeanVarianceImage& b) {
  const size_t values = size_t(std::max(a.width, 0)) * size_t(std::max(a.height, 0)) * 3;
  if (a.width <= 0 || a.height <= 0 || a.width != b.width || a.height != b.height ||
      a.mean.size() != values || a.variance.size() != values || b.mean.size() != values ||
      b.variance.size() != values)
    throw std::invalid_argument("compare_renders: images of different or inconsistent sizes");
}

// Means of A and B over the rectangle [x0,x1) x [y0,y1) and the z of their difference, treating
// pixel means as independent (variance of a region mean = sum of variances / n^2).
struct RegionZ {
  double mean_a[3] = {0, 0, 0};
  double mean_b[3] = {0, 0, 0};
  double z[3] = {0, 0, 0};
};

RegionZ region_z(const MeanVarianceImage& a, const MeanVarianceImage& b, int x0, int y0, int x1, int y1) {
  double sum_a[3] = {0, 0, 0}, sum_b[3] = {0, 0, 0}, sum_var[3] = {0, 0, 0};
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x)
      for (int c = 0; c < 3; ++c) {
        const size_t i = (size_t(y) * a.width + x) * 3 + c;
        sum_a[c] += a.mean[i];
        sum_b[c] += b.mean[i];
        sum_var[c] += double(a.variance[i]) + double(b.variance[i]);
      }
  const double n = double(x1 - x0) * double(y1 - y0);
  RegionZ r;
  for (int c = 0; c < 3; ++c) {
    r.mean_a[c] = sum_a[c] / n;
    r.mean_b[c] = sum_b[c] / n;
    r.z[c] = welch_z(r.mean_a[c], r.mean_b[c], sum_var[c] / (n * n));
  }
  return r;
}

// The per-pixel acceptance test and the same-seed equality count, in one pass.
void test_pixels(const MeanVarianceImage& a, const MeanVarianceImage& b, CompareResult& r) {
  const double channel_alpha = sidak_alpha(r.options.pixel_alpha, 3);
  r.pixel_z_critical = critical_z(channel_alpha);
  r.pixel_count = int64_t(a.width) * a.height;
  int64_t equal = 0;
  for (int64_t p = 0; p < r.pixel_count; ++p) {
    bool accepted = true, same = true;
    for (int c = 0; c < 3; ++c) {
      const size_t i = size_t(p) * 3 + c;
      const double z = welch_z(a.mean[i], b.mean[i], double(a.variance[i]) + double(b.variance[i]));
      accepted = accepted && accepts(z, channel_alpha);
      same = same && agree_within(a.mean[i], b.mean[i], r.options.tolerance);
    }
    r.accepted_pixels += accepted ? 1 : 0;
    equal += same ? 1 : 0;
  }
  r.accept_fraction = double(r.accepted_pixels) / double(r.pixel_count);
  r.pixels_pass = r.accept_fraction >= r.options.min_accept;
  r.equal_fraction = double(equal) / double(r.pixel_count);
  r.same_seed_pass = r.equal_fraction >= r.options.min_equal;
}

BlockScaleResult test_block_scale(const MeanVarianceImage& a, const MeanVarianceImage& b, int size,
                                  double family_alpha) {
  BlockScaleResult r;
  r.block_size = size;
  const int blocks_x = (a.width + size - 1) / size, blocks_y = (a.height + size - 1) / size;
  r.block_count = blocks_x * blocks_y;
  const double alpha = sidak_alpha(family_alpha, 3.0 * r.block_count);
  r.z_critical = critical_z(alpha);
  double worst_score = -1;
  for (int y0 = 0; y0 < a.height; y0 += size)
    for (int x0 = 0; x0 < a.width; x0 += size) {
      const int x1 = std::min(x0 + size, a.width), y1 = std::min(y0 + size, a.height);
      const RegionZ block = region_z(a, b, x0, y0, x1, y1);
      bool rejected = false;
      for (int c = 0; c < 3; ++c) {
        rejected = rejected || !accepts(block.z[c], alpha);
        const double score = std::isnan(block.z[c]) ? kInf : std::abs(block.z[c]);
        if (score > worst_score) {
          worst_score = score;
          r.worst = WorstBlock{x0, y0, x1 - x0, y1 - y0, c, block.z[c]};
        }
      }
      r.rejected_blocks += rejected ? 1 : 0;
    }
  r.pass = r.rejected_blocks == 0;
  return r;
}

ImageMeanResult test_image_mean(const MeanVarianceImage& a, const MeanVarianceImage& b, double family_alpha) {
  const RegionZ whole = region_z(a, b, 0, 0, a.width, a.height);
  const double alpha = sidak_alpha(family_alpha, 3);
  ImageMeanResult r;
  r.z_critical = critical_z(alpha);
  r.pass = true;
  for (int c = 0; c < 3; ++c) {
    r.mean_a[c] = whole.mean_a[c];
    r.mean_b[c] = whole.mean_b[c];
    r.z[c] = whole.z[c];
    r.pass = r.pass && accepts(whole.z[c], alpha);
  }
  return r;
}

const char* verdict(bool pass) { return pass ? "PASS" : "FAIL"; }

std::string describe_file(const ComparedFile& f, const CompareResult& r) {
  std::string s = f.path + " (" + std::to_string(r.width) + "x" + std::to_string(r.height);
  s += f.spp ? ", " + std::to_string(*f.spp) + " spp)" : ", spp unknown)";
  return s;
}

void append_block_lines(std::string& out, const CompareResult& r) {
  for (const BlockScaleResult& s : r.scales) {
    const WorstBlock& w = s.worst;
    appendf(out, "blocks %dx%d: %d of %d reject (a channel rejects at |z| >= %.2f); worst at (%d,%d) %dx%d %s z=%+.2f  %s\n",
            s.block_size, s.block_size, s.rejected_blocks, s.block_count, s.z_critical, w.x, w.y,
            w.width, w.height, kChannelNames[w.channel], w.z, verdict(s.pass));
  }
}

// JSON has no infinity or NaN: those become null.
nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json json_triple(const double v[3]) { return {json_number(v[0]), json_number(v[1]), json_number(v[2])}; }

nlohmann::json json_file(const ComparedFile& f) {
  return {{"path", f.path}, {"spp", f.spp ? nlohmann::json(*f.spp) : nlohmann::json(nullptr)}};
}

}  // namespace

double two_sided_p_value(double z) { return std::erfc(std::abs(z) / std::sqrt(2.0)); }

double sidak_alpha(double family_alpha, double tests) {
  // 1 - (1 - alpha)^(1/tests), in a form that keeps its precision for tiny results.
  return -std::expm1(std::log1p(-family_alpha) / tests);
}

double critical_z(double alpha) {
  // Bisection on the monotone p-value: the smallest |z| whose p-value is <= alpha.
  double lo = 0, hi = 40;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (two_sided_p_value(mid) > alpha ? lo : hi) = mid;
  }
  return hi;
}

CompareResult compare_renders(const MeanVarianceImage& a, const MeanVarianceImage& b,
                              const CompareOptions& options) {
  check_same_shape(a, b);
  CompareResult r;
  r.options = options;
  r.width = a.width;
  r.height = a.height;
  test_pixels(a, b, r);
  r.statistical_pass = r.pixels_pass;
  for (const int size : options.block_sizes) {
    if (size <= 0) throw std::invalid_argument("compare_renders: block sizes must be positive");
    r.scales.push_back(test_block_scale(a, b, size, options.alpha));
    r.statistical_pass = r.statistical_pass && r.scales.back().pass;
  }
  r.image_mean = test_image_mean(a, b, options.alpha);
  r.statistical_pass = r.statistical_pass && r.image_mean.pass;
  r.pass = options.same_seed ? r.same_seed_pass : r.statistical_pass;
  return r;
}

std::vector<float> pixel_average_z(const MeanVarianceImage& a, const MeanVarianceImage& b) {
  check_same_shape(a, b);
  std::vector<float> z(size_t(a.width) * a.height);
  for (size_t p = 0; p < z.size(); ++p) {
    double mean_a = 0, mean_b = 0, variance = 0;
    for (size_t i = p * 3; i < p * 3 + 3; ++i) {
      mean_a += a.mean[i] / 3.0;
      mean_b += b.mean[i] / 3.0;
      variance += (double(a.variance[i]) + double(b.variance[i])) / 9.0;
    }
    z[p] = float(welch_z(mean_a, mean_b, variance));
  }
  return z;
}

std::vector<unsigned char> z_to_colour_ramp(const std::vector<float>& z, double saturate_at) {
  std::vector<unsigned char> rgb(z.size() * 3, 0);
  for (size_t p = 0; p < z.size(); ++p) {
    if (std::isnan(z[p])) continue;  // black
    const double t = std::clamp(double(z[p]) / saturate_at, -1.0, 1.0);
    const double colour[3] = {t < 0 ? 1 + t : 1.0, 1 - std::abs(t), t > 0 ? 1 - t : 1.0};
    for (int c = 0; c < 3; ++c) rgb[p * 3 + c] = static_cast<unsigned char>(std::lround(colour[c] * 255.0));
  }
  return rgb;
}

std::string format_compare_report(const CompareResult& r, const ComparedFile& a, const ComparedFile& b) {
  const CompareOptions& o = r.options;
  std::string out = "A: " + describe_file(a, r) + "\nB: " + describe_file(b, r) + "\n";
  if (o.same_seed) out += "mode: same-seed (the statistical verdicts below are for information only)\n";
  appendf(out, "pixels: %lld of %lld accept (%.3f%%; need >= %.3f%%; a channel rejects at |z| >= %.2f)  %s\n",
          (long long)r.accepted_pixels, (long long)r.pixel_count, 100.0 * r.accept_fraction,
          100.0 * o.min_accept, r.pixel_z_critical, verdict(r.pixels_pass));
  append_block_lines(out, r);
  const ImageMeanResult& m = r.image_mean;
  out += "image mean:";
  for (int c = 0; c < 3; ++c)
    appendf(out, " %s %.6g vs %.6g (diff %+.3g, z=%+.2f)%s", kChannelNames[c], m.mean_a[c], m.mean_b[c],
            m.mean_a[c] - m.mean_b[c], m.z[c], c < 2 ? ";" : "");
  appendf(out, " (rejects at |z| >= %.2f)  %s\n", m.z_critical, verdict(m.pass));
  appendf(out, "statistical verdict: %s\n", verdict(r.statistical_pass));
  appendf(out, "same seed: %.4f%% of pixels equal within %g relative (need >= %.3f%%)%s\n",
          100.0 * r.equal_fraction, o.tolerance, 100.0 * o.min_equal,
          o.same_seed ? (r.same_seed_pass ? "  PASS" : "  FAIL") : " (not the criterion)");
  appendf(out, "result: %s\n", verdict(r.pass));
  return out;
}

std::string compare_report_json(const CompareResult& r, const ComparedFile& a, const ComparedFile& b) {
  const CompareOptions& o = r.options;
  const ImageMeanResult& m = r.image_mean;
  const double difference[3] = {m.mean_a[0] - m.mean_b[0], m.mean_a[1] - m.mean_b[1], m.mean_a[2] - m.mean_b[2]};
  nlohmann::json scales = nlohmann::json::array();
  for (const BlockScaleResult& s : r.scales) {
    const WorstBlock& w = s.worst;
    scales.push_back({{"size", s.block_size},
                      {"count", s.block_count},
                      {"rejected", s.rejected_blocks},
                      {"z_critical", json_number(s.z_critical)},
                      {"worst", {{"x", w.x}, {"y", w.y}, {"width", w.width}, {"height", w.height},
                                 {"channel", kChannelNames[w.channel]}, {"z", json_number(w.z)}}},
                      {"pass", s.pass}});
  }
  const nlohmann::json report = {
      {"mode", o.same_seed ? "same-seed" : "statistical"},
      {"a", json_file(a)},
      {"b", json_file(b)},
      {"width", r.width},
      {"height", r.height},
      {"pixels", {{"count", r.pixel_count}, {"accepted", r.accepted_pixels},
                  {"accept_fraction", json_number(r.accept_fraction)}, {"min_accept", json_number(o.min_accept)},
                  {"pixel_alpha", json_number(o.pixel_alpha)}, {"z_critical", json_number(r.pixel_z_critical)},
                  {"pass", r.pixels_pass}}},
      {"block_scales", scales},
      {"image_mean", {{"a", json_triple(m.mean_a)}, {"b", json_triple(m.mean_b)},
                      {"difference", json_triple(difference)}, {"z", json_triple(m.z)},
                      {"alpha", json_number(o.alpha)}, {"z_critical", json_number(m.z_critical)},
                      {"pass", m.pass}}},
      {"statistical_pass", r.statistical_pass},
      {"same_seed", {{"decides", o.same_seed}, {"tolerance", json_number(o.tolerance)},
                     {"equal_fraction", json_number(r.equal_fraction)}, {"min_equal", json_number(o.min_equal)},
                     {"pass", r.same_seed_pass}}},
      {"pass", r.pass},
  };
  return report.dump(2) + "\n";
}

}  // namespace clpt
