// Statistical comparison of two renders of the same scene, from their per-pixel means and the
// variances of those means (the R,G,B and variance.* channels `clpt render` writes). Pure
// functions over float arrays, no file I/O, so tests can run them on synthetic images.
//
// Model: every pixel channel mean is an independent, approximately normal estimate with a known
// variance of the mean. If both renders estimate the same image, the Welch statistic
// z = (a - b) / sqrt(var_a + var_b) is standard normal, for a pixel and for the mean of any
// region (whose variance is sum(var) / n^2). Three tests use it:
//   pixels  each pixel accepts when all 3 channels do (Sidak over the channels); the image passes
//           when a large enough fraction of pixels accept. Catches local gross errors.
//   blocks  means of non-overlapping square blocks at several scales (Sidak over all blocks and
//           channels of a scale); a scale passes when no block rejects. Catches a small shift
//           over a region that no single pixel shows.
//   mean    the whole-image mean per channel (Sidak over the 3 channels).
// Same-seed mode instead asks that nearly every pixel be equal within a relative tolerance (two
// devices or execution forms rendering the same samples); the tests above are only reported.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "render/film.h"  // MeanVarianceImage

namespace clpt {

struct CompareOptions {
  // Family-wise false-rejection rate of one pixel's test (Sidak-split over its 3 channels). It
  // must sit well below 1 - min_accept: with 0.01, 1% of the pixels of two equal-distribution
  // renders would reject and no image could reach 99.75% acceptance.
  double pixel_alpha = 0.001;
  double min_accept = 0.9975;  // fraction of accepting pixels needed to pass
  double alpha = 0.01;         // family-wise, per block scale and for the whole-image mean
  std::vector<int> block_sizes{16, 32, 64};
  bool same_seed = false;     // decide by per-pixel equality instead of the statistics
  double tolerance = 1e-4;    // same-seed: |a - b| <= tolerance * max(|a|, |b|, 1e-6)
  double min_equal = 0.99;    // same-seed: fraction of equal pixels needed to pass
};

// Where and how far the worst block of a scale is off (largest |z|; NaN counts as worst).
struct WorstBlock {
  int x = 0, y = 0;           // top-left pixel
  int width = 0, height = 0;  // smaller than the block size at the right and bottom edges
  int channel = 0;            // 0 = R, 1 = G, 2 = B
  double z = 0;               // signed: positive when A is brighter
};

struct BlockScaleResult {
  int block_size = 0;
  int block_count = 0;
  int rejected_blocks = 0;  // blocks with at least one rejecting channel
  double z_critical = 0;    // a channel rejects when |z| >= this (or z is NaN)
  WorstBlock worst;
  bool pass = false;
};

struct ImageMeanResult {
  double mean_a[3] = {0, 0, 0};
  double mean_b[3] = {0, 0, 0};
  double z[3] = {0, 0, 0};  // (mean_a - mean_b) / sqrt(var_a + var_b) of the image means
  double z_critical = 0;
  bool pass = false;
};

struct CompareResult {
  CompareOptions options;  // as used, for the report
  int width = 0, height = 0;
  int64_t pixel_count = 0;
  int64_t accepted_pixels = 0;
  double accept_fraction = 0;
  double pixel_z_critical = 0;  // a pixel channel rejects when |z| >= this
  bool pixels_pass = false;
  std::vector<BlockScaleResult> scales;
  ImageMeanResult image_mean;
  bool statistical_pass = false;  // pixels, every block scale and the image mean pass
  double equal_fraction = 0;      // pixels whose 3 channels agree within options.tolerance
  bool same_seed_pass = false;
  bool pass = false;  // same_seed_pass in same-seed mode, else statistical_pass
};

// Compares A and B. Contract: equal positive sizes, mean and variance of width*height*3 floats
// each (throws std::invalid_argument otherwise); variances are non-negative. A channel with
// var_a + var_b == 0 accepts iff a and b agree within 1e-6 relative.
CompareResult compare_renders(const MeanVarianceImage& a, const MeanVarianceImage& b,
                              const CompareOptions& options);

// Per pixel, the signed z of the difference of the channel averages (a grey "luminance-ish"
// value), positive when A is brighter; +-infinity for a zero-variance pixel that differs, NaN
// where an input is NaN. Same contract as compare_renders.
std::vector<float> pixel_average_z(const MeanVarianceImage& a, const MeanVarianceImage& b);

// 8-bit RGB false colour for z values: blue (negative) - white (0) - red (positive), saturating
// at |z| = saturate_at; NaN is black.
std::vector<unsigned char> z_to_colour_ramp(const std::vector<float>& z, double saturate_at = 4.0);

// What the report says about each input file.
struct ComparedFile {
  std::string path;
  std::optional<uint64_t> spp;  // from the clpt:spp metadata, when present
};

// The human-readable report (several lines, ending with "result: PASS" or "result: FAIL").
std::string format_compare_report(const CompareResult& r, const ComparedFile& a, const ComparedFile& b);

// The same figures as one JSON object; non-finite numbers become null.
std::string compare_report_json(const CompareResult& r, const ComparedFile& a, const ComparedFile& b);

// Two-sided standard-normal p-value of z; NaN for NaN.
double two_sided_p_value(double z);
// Per-test alpha so that `tests` independent tests have family-wise rate family_alpha (Sidak).
double sidak_alpha(double family_alpha, double tests);
// The |z| at which a two-sided test at level alpha starts to reject.
double critical_z(double alpha);

}  // namespace clpt
