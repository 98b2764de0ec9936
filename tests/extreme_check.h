// Renders an extreme scene (tests/extreme_scenes.h) in a precision preset and judges its image.
#pragma once

#include "render_test_util.h"  // sidak_z, book_regions

#include <cstdint>
#include <string>

#include "extreme_scenes.h"
#include "kernels/kernel_options.h"

namespace clpt::test {

struct ExtremeResult {
  bool pass = false;
  double worst_relative_error = 0;  // over the compared region means / pixels
  double worst_z = 0;               // statistical checks: worst |difference| / sigma (0 otherwise)
  uint64_t dropped = 0;             // NaN/Inf samples the film dropped (any makes the row fail)
  double render_seconds = 0;
  std::string detail;               // what failed, or the worst comparison
};

// Everything a run of checks shares: the preset, the seed, and the number of statistical
// comparisons in the whole run, for the Sidak-corrected z threshold (family-wise alpha 0.01).
struct ExtremeRun {
  Precision precision = Precision::Robust;
  uint64_t seed = 2015;
  int family_comparisons = 1;
};

// Statistical comparisons one extreme contributes to the family (for ExtremeRun).
int comparisons_of(const Extreme& extreme);


// Region means of zero-variance regions (the light) may differ by this relative error, the float
// rounding of a scaled emission, on top of the statistical allowance.
constexpr double kExactTolerance = 1e-6;

ExtremeResult check_extreme(const Extreme& extreme, const ExtremeRun& run);

}  // namespace clpt::test
