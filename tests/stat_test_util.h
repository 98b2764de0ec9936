// Chi-square goodness of fit for the sampling tests (BSDF, light and environment samplers against
// their own densities).
#pragma once

#include <vector>

namespace clpt::test {

// Upper tail of the chi-square distribution with `dof` degrees of freedom at `statistic`
// (Wilson-Hilferty's cube-root normal approximation: accurate for dof in the tens and more).
double chi2_survival(double statistic, double dof);

// p-value of Pearson's statistic of `observed` against `expected` counts (the same cells), the
// cells expecting fewer than `min_expected` pooled into one cell.
double chi2_pooled_p_value(const std::vector<double>& observed, const std::vector<double>& expected,
                           double min_expected = 5);

}  // namespace clpt::test
