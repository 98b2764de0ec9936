#include "stat_test_util.h"

#include <cmath>
#include <cstddef>

namespace clpt::test {

double chi2_survival(double statistic, double dof) {
  const double z = (std::cbrt(statistic / dof) - (1 - 2 / (9 * dof))) / std::sqrt(2 / (9 * dof));
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

double chi2_pooled_p_value(const std::vector<double>& observed, const std::vector<double>& expected,
                           double min_expected) {
  double statistic = 0, pooled_observed = 0, pooled_expected = 0;
  int cells = 0;
  for (size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < min_expected) {
      pooled_observed += observed[i];
      pooled_expected += expected[i];
      continue;
    }
    statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++cells;
  }
  if (pooled_expected > 0) {
    statistic += (pooled_observed - pooled_expected) * (pooled_observed - pooled_expected) / pooled_expected;
    ++cells;
  }
  return chi2_survival(statistic, cells - 1);
}

}  // namespace clpt::test
