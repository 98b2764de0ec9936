#include "render/progress.h"

#include <algorithm>
#include <cstdio>

namespace clpt {
namespace {

// Seconds to go from spp_done to `spp` at this run's rate; negative when unknown.
double eta_to_spp(const ProgressState& s, uint64_t spp) {
  if (s.spp_this_run == 0 || spp == 0) return -1;
  return s.elapsed_s * double(spp - std::min(s.spp_done, spp)) / double(s.spp_this_run);
}

double least_known(double a, double b) { return a < 0 ? b : (b < 0 ? a : std::min(a, b)); }

}  // namespace

double progress_eta_s(const ProgressState& s) {
  double eta = eta_to_spp(s, s.spp_target);
  if (s.target_error > 0) eta = least_known(eta, eta_to_spp(s, s.predicted_spp));
  if (s.time_limit_s > 0) eta = least_known(eta, std::max(0.0, s.time_limit_s - s.elapsed_s));
  return eta;
}

void Progress::update(const ProgressState& s) {
  if (!enabled_) return;
  char target[32] = "";
  if (s.spp_target > 0) std::snprintf(target, sizeof target, "/%llu", (unsigned long long)s.spp_target);
  char error[64] = "";
  if (s.target_error > 0) {
    if (s.estimate.valid)
      std::snprintf(error, sizeof error, "  error %.2f%% (target %.2f%%)", 100 * s.estimate.relative_rmse_upper,
                    100 * s.target_error);
    else
      std::snprintf(error, sizeof error, "  error ? (target %.2f%%)", 100 * s.target_error);
  }
  std::fprintf(stderr, "\r  pass %d  %llu%s spp  %.2f M samples/s in passes%s  elapsed %.1f s  ETA %.1f s   ", s.passes,
               (unsigned long long)s.spp_done, target, s.samples_per_s * 1e-6, error, s.elapsed_s,
               std::max(0.0, progress_eta_s(s)));
  std::fflush(stderr);
  drawn_ = true;
}

void Progress::finish() {
  if (enabled_ && drawn_) std::fprintf(stderr, "\n");
  drawn_ = false;
}

}  // namespace clpt
