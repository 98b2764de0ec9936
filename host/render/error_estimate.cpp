// The half-film error estimate (error_estimate.h): one pass over the pixels, in double.
#include "render/error_estimate.h"

#include <cmath>

namespace clpt {

ErrorEstimate estimate_error(const Film& film) {
  ErrorEstimate e;
  e.half_spp[0] = film.half_samples_per_pixel(0);
  e.half_spp[1] = film.half_samples_per_pixel(1);
  if (!film.between_passes() || e.half_spp[0] == 0 || e.half_spp[1] == 0) return e;
  const auto& sum = film.sums();
  const auto& valid = film.valid_counts();
  const auto& sum1 = film.half1_sums();
  const auto& valid1 = film.half1_valid_counts();
  double mean_sum = 0, term_sum = 0, term_sq_sum = 0;
  size_t pixels_with_samples = 0, terms = 0;
  for (size_t p = 0; p < valid.size(); ++p) {
    const double n = valid[p], n1 = valid1[p], n0 = n - n1;
    if (n <= 0) continue;
    ++pixels_with_samples;
    for (int c = 0; c < 3; ++c) mean_sum += sum[p * 3 + c] / n;
    if (n0 <= 0 || n1 <= 0) continue;  // every sample of a half dropped (NaN/Inf): no difference
    const double weight = n0 * n1 / (n * n);
    for (int c = 0; c < 3; ++c) {
      const double s1 = sum1[p * 3 + c];
      const double d = (sum[p * 3 + c] - s1) / n0 - s1 / n1;
      const double term = d * d * weight;
      term_sum += term;
      term_sq_sum += term * term;
      ++terms;
    }
  }
  if (terms == 0 || pixels_with_samples == 0) return e;
  e.image_mean = mean_sum / double(3 * pixels_with_samples);
  e.mse = term_sum / double(terms);
  const double term_variance = std::max(0.0, term_sq_sum / double(terms) - e.mse * e.mse);
  e.mse_standard_error = std::sqrt(term_variance / double(terms));
  if (!(e.image_mean > 0)) return e;
  e.relative_rmse = std::sqrt(e.mse) / e.image_mean;
  e.relative_rmse_upper = std::sqrt(e.mse + 2 * e.mse_standard_error) / e.image_mean;
  e.valid = true;
  return e;
}

}  // namespace clpt
