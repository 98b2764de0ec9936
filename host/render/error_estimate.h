// clpt's own estimate of a film's error: the relative RMSE of the image against the converged
// image (the RMSE over pixels and channels, divided by the converged image's mean over pixels and
// channels), estimated from the film's two half-films (film.h) without any reference.
//
// Why the halves and not the per-pixel variance: the pixel mean is m = (n0 m0 + n1 m1) / n of two
// independent half-means with the same expectation, so E[(m0 - m1)^2] = Var m0 + Var m1, and for
// equal halves (n0 = n1) Var m = (Var m0 + Var m1) / 4 exactly: (m0 - m1)^2 / 4 is an unbiased
// estimate of the pixel's squared error whatever the sampler's stratification inside a half
// (the sample variance s^2/n assumes independent samples and overstates a stratified mean's
// error 1.4-1.6x), and whatever the number of samples (s^2 of one or two samples is mostly 0 or
// noise). For unequal halves the factor n0 n1 / n^2 replaces 1/4 (exact when the variance of a
// half scales as 1/n). Fireflies: a rare large sample lands in one half and shows in the
// difference; the estimate is the mean of many such terms, and the stopping rule uses an upper
// bound, the mean plus two of its standard errors over the terms, which a few dominant terms
// raise. Docs: docs/target-error.md.
#pragma once

#include <cstdint>

#include "render/film.h"

namespace clpt {

struct ErrorEstimate {
  bool valid = false;            // false until both halves hold samples
  double mse = 0;                // estimated mean squared error over pixels and channels
  double mse_standard_error = 0; // standard error of `mse` (from the spread of its terms)
  double image_mean = 0;         // the film's mean over pixels and channels
  double relative_rmse = 0;      // sqrt(mse) / image_mean
  double relative_rmse_upper = 0;  // sqrt(mse + 2 standard errors) / image_mean: what stops a render
  uint64_t half_spp[2] = {0, 0};   // samples per pixel of each half
};

// The estimate of `film` (between passes). Invalid while a half is empty or the image is black.
ErrorEstimate estimate_error(const Film& film);

}  // namespace clpt
